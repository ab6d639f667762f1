// SPDX-License-Identifier: MIT
#include "io/common/number_writer.hpp"
#include "io/common/layout.hpp"

#include <fmt/format.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace keyrot {

namespace {

constexpr char digit_pairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

/// The 8 decimal digits of v < 10^8, leading zeros included, as characters
/// in one 64-bit word, the first in its lowest byte: halves of 4 digits,
/// lanes of 2, then of 1 (divisions by constants as multiplications that are
/// exact in these ranges: checked against printf for every v < 10^8).
std::uint64_t eight_digits(std::uint32_t v) noexcept {
    const std::uint64_t halves = v / 10000 | std::uint64_t{v % 10000} << 32;
    const std::uint64_t hundreds = (halves * 10486) >> 20 & 0x0000007F0000007F;  // each half / 100
    const std::uint64_t pairs = (halves - 100 * hundreds) << 16 | hundreds;
    const std::uint64_t tens = (pairs * 103) >> 10 & 0x000F000F000F000F;  // each pair / 10
    return ((pairs - 10 * tens) << 8 | tens) + 0x3030303030303030;
}

/// Writes the 8 characters of eight_digits at out.
void store_eight(char* out, std::uint64_t digits) noexcept {
    if constexpr (std::endian::native == std::endian::little) {
        std::memcpy(out, &digits, 8);
    } else {
        for (int i = 0; i < 8; ++i) out[i] = static_cast<char>(digits >> (8 * i));
    }
}

/// Writes the 16 decimal digits of v < 10^16, leading zeros included: two
/// halves of 8 digits, all digits in flight at once (divisions by constants
/// as multiplications that are exact in these ranges: checked against printf
/// for every half v < 10^8).
void write_sixteen(char* out, std::uint64_t v) noexcept {
#if defined(__SSE2__)
    // Each half in the 16-bit lanes of a register: its quarters of 4 digits
    // spread over four lanes each, the lanes divided by 1000, 100, 10 and 1
    // (floor(x * m / 2^16) twice), less 10 times the lane before.
    const auto eight = [](std::uint32_t half) {
        const __m128i x = _mm_cvtsi32_si128(static_cast<int>(half));
        const __m128i high = _mm_srli_epi64(_mm_mul_epu32(x, _mm_set1_epi32(static_cast<int>(0xd1b71759))), 45);
        const __m128i low = _mm_sub_epi32(x, _mm_mul_epu32(high, _mm_set1_epi32(10000)));
        const __m128i quarters = _mm_slli_epi64(_mm_unpacklo_epi16(high, low), 2);  // times 4
        const __m128i pairs = _mm_unpacklo_epi16(quarters, quarters);
        const __m128i spread = _mm_unpacklo_epi32(pairs, pairs);
        const __m128i divided = _mm_mulhi_epu16(
            _mm_mulhi_epu16(spread, _mm_setr_epi16(8389, 5243, 13108, -32768, 8389, 5243, 13108, -32768)),
            _mm_setr_epi16(1 << 7, 1 << 11, 1 << 13, -32768, 1 << 7, 1 << 11, 1 << 13, -32768));
        return _mm_sub_epi16(divided, _mm_slli_epi64(_mm_mullo_epi16(divided, _mm_set1_epi16(10)), 16));
    };
    const __m128i digits = _mm_packus_epi16(eight(static_cast<std::uint32_t>(v / 100000000)),
                                            eight(static_cast<std::uint32_t>(v % 100000000)));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out), _mm_add_epi8(digits, _mm_set1_epi8('0')));
#else
    store_eight(out, eight_digits(static_cast<std::uint32_t>(v / 100000000)));
    store_eight(out + 8, eight_digits(static_cast<std::uint32_t>(v % 100000000)));
#endif
}

constexpr std::uint64_t powers_of_ten[18] = {1,
                                             10,
                                             100,
                                             1000,
                                             10000,
                                             100000,
                                             1000000,
                                             10000000,
                                             100000000,
                                             1000000000,
                                             10000000000,
                                             100000000000,
                                             1000000000000,
                                             10000000000000,
                                             100000000000000,
                                             1000000000000000,
                                             10000000000000000,
                                             100000000000000000};

/// The number of decimal digits of v < 10^17 (1 for 0).
int digit_count(std::uint64_t v) noexcept {
    const int bits = 64 - std::countl_zero(v | 1);
    const int count = (bits * 1233 >> 12) + 1;  // floor(log10(2^bits)) + 1: exact or one too many
    return (v | 1) < powers_of_ten[count - 1] ? count - 1 : count;  // (v | 1: zero has one digit)
}

/// Writes the 17 decimal digits of v < 10^17, leading zeros included.
void write_seventeen(char* out, std::uint64_t v) noexcept {
    out[0] = static_cast<char>('0' + v / 10000000000000000);
    write_sixteen(out + 1, v % 10000000000000000);
}

/// The decimal digits of a significand (at most 17 of them, as Dragonbox
/// gives for a double), written as 17 with leading zeros and copied in
/// fixed-size blocks: no loop or call depends on the digit count.
class significand_digits {
public:
    explicit significand_digits(std::uint64_t v) noexcept : count_(digit_count(v)) { write_seventeen(digits_, v); }
    int count() const noexcept { return count_; }
    /// Writes digits [from, count) at out, and up to 16 bytes of scratch after them.
    void copy(char* out, int from = 0) const noexcept {
        std::memcpy(out, digits_ + 17 - count_ + from, 17);
    }

private:
    char digits_[17 + 17];  // the copies may read past the digits
    int count_;
};

/// |v| < 10^17. `out` needs 18 bytes of room.
char* write_integer(char* out, std::int64_t v) noexcept {
    if (v < 0) *out++ = '-';
    const auto magnitude = static_cast<std::uint64_t>(v < 0 ? -v : v);
    if (magnitude < powers_of_ten[8]) {  // frame numbers: in one word, its leading zeros shifted out
        const int count = digit_count(magnitude);
        store_eight(out, eight_digits(static_cast<std::uint32_t>(magnitude)) >> (8 * (8 - count)));
        return out + count;
    }
    const significand_digits digits(magnitude);
    digits.copy(out);
    return out + digits.count();
}

/// The digits with `point` of them before the decimal point (fewer than all
/// of them, and -point <= 16): dd.ddd or 0.000ddd. `out` needs 36 bytes of
/// room.
char* write_with_point(char* out, const significand_digits& digits, int point) noexcept {
    if (point > 0) {  // dd.ddd
        digits.copy(out);
        out[point] = '.';
        digits.copy(out + point + 1, point);
        return out + digits.count() + 1;
    }
    out[0] = '0', out[1] = '.';  // 0.000ddd
    std::memset(out + 2, '0', 16);
    digits.copy(out + 2 - point);
    return out + 2 - point + digits.count();
}

/// The shortest digits that read back to v (Dragonbox, the algorithm fmt's
/// "{}" uses), laid out exactly as "{}" lays them out: fixed notation for
/// decimal exponents in [-4, 16), else d.ddde+XX. Writing the layout here
/// rather than through fmt's general formatter takes a third off the
/// writers' hot path (tests/io/common/number_writer_test.cpp compares it
/// with fmt). `out` needs 40 bytes of room.
char* write_shortest(char* out, double v) noexcept {
    // Signs of rotation components come at random: no branch to mispredict.
    *out = '-';
    out += std::signbit(v);
    v = std::fabs(v);
    // An internal of fmt: pinned to the versions
    // tests/io/common/number_writer_test.cpp has compared digit for digit
    // with fmt's own "{}".
    static_assert(FMT_VERSION >= 90000 && FMT_VERSION < 100000,
                  "fmt::detail::dragonbox::to_decimal is fmt 9's: run the number writer's tests before taking another fmt");
    const auto decimal = fmt::detail::dragonbox::to_decimal(v);
    const int count = digit_count(decimal.significand);
    const int point = decimal.exponent + count;  // digits before the decimal point
    // 0.ddd or 0.000ddd with most digits (a rotation's components): the 17
    // digits stored where they end, their leading zeros after `out`, rather
    // than staged and copied (the copy's load spans the two stores that
    // staged them, which the processor cannot forward: it waits for them).
    if (point <= 0 && point - 1 >= -4 && count - point >= 15) {
        char* const end = out + 2 - point + count;
        std::memset(out, '0', 16);  // the zeros after the point that the digits' own do not reach
        write_seventeen(end - 17, decimal.significand);
        out[0] = '0', out[1] = '.';
        return end;
    }
    const significand_digits digits(decimal.significand);
    if (point - 1 < -4 || point - 1 >= 16) {  // d[.ddd]e+XX
        digits.copy(out + 1);
        out[0] = out[1];
        out[1] = '.';
        out += count > 1 ? count + 1 : 1;
        *out++ = 'e';
        *out++ = point - 1 < 0 ? '-' : '+';
        const int exponent = std::abs(point - 1);
        if (exponent >= 100) *out++ = static_cast<char>('0' + exponent / 100);
        std::memcpy(out, digit_pairs + exponent % 100 * 2, 2);
        return out + 2;
    }
    if (decimal.exponent >= 0) {  // ddd000
        digits.copy(out);
        std::memset(out + count, '0', static_cast<std::size_t>(decimal.exponent));
        return out + point;
    }
    return write_with_point(out, digits, point);
}

/// For write_fixed: a whole number of up to 1024 bits (32-bit limbs, least
/// significant first, `n` of them, destroyed) divided by 10^decimals, in
/// fixed notation without trailing zeros. The number has more digits than
/// `decimals`.
char* write_limbs_fixed(char* out, bool negative, std::uint32_t* limbs, int n, int decimals) noexcept {
    char digits[35 * 9];  // 2^1024 has 309 digits
    char *begin = std::end(digits), *end = std::end(digits);
    while (n > 0) {  // the number divided by 10^9, the remainder's 9 digits written
        std::uint64_t rest = 0;
        for (int i = n - 1; i >= 0; --i) {
            const std::uint64_t part = rest << 32 | limbs[i];
            limbs[i] = static_cast<std::uint32_t>(part / 1000000000);
            rest = part % 1000000000;
        }
        while (n > 0 && limbs[n - 1] == 0) --n;
        for (int i = 0; i < 9; ++i) *--begin = static_cast<char>('0' + rest % 10), rest /= 10;
    }
    while (*begin == '0') ++begin;
    while (decimals > 0 && end[-1] == '0') --end, --decimals;
    if (negative) *out++ = '-';
    out = std::copy(begin, end - decimals, out);
    if (decimals == 0) return out;
    *out++ = '.';
    return std::copy(end - decimals, end, out);
}

/// v rounded to `decimals` digits after the point (ties to even, on the
/// exact binary value), trailing zeros dropped, as fmt's "{:.Nf}" and
/// printf's "%.Nf" round. Exact in integers: v = m 2^-k, so v 10^N rounds to
/// the quotient of m 10^N (< 2^110) by 2^k; a v of 2^52 or more is the whole
/// number m 2^-k. Not through fmt's fixed notation: its fallback to big
/// integers, taken for many numbers, is slow (a hundred times as slow for
/// 1e300). `out` needs max_number_chars bytes of room.
char* write_fixed(char* out, double v, int decimals) noexcept {
    __extension__ using uint128 = unsigned __int128;
    const auto bits = std::bit_cast<std::uint64_t>(v);
    const int biased = static_cast<int>(bits >> 52 & 0x7ff);
    const std::uint64_t fraction = bits & ((std::uint64_t{1} << 52) - 1);
    const std::uint64_t m = biased == 0 ? fraction : fraction | std::uint64_t{1} << 52;
    const int k = biased == 0 ? 1074 : 1075 - biased;  // v = m 2^-k
    if (k <= 0) {  // m 2^-k, whole
        std::uint32_t limbs[33] = {};
        const int word = -k / 32;
        const uint128 shifted = uint128{m} << (-k % 32);  // < 2^84: three limbs
        for (int i = 0; i < 3; ++i) limbs[word + i] = static_cast<std::uint32_t>(shifted >> (32 * i));
        return write_limbs_fixed(out, v < 0, limbs, word + 3, 0);
    }
    uint128 rounded = 0;
    if (k < 111) {  // else m 10^N < 2^110 < half of 2^k: rounds to 0
        const uint128 scaled = uint128{m} * powers_of_ten[decimals];
        rounded = scaled >> k;
        const uint128 rest = scaled - (rounded << k), half = uint128{1} << (k - 1);
        if (rest > half || (rest == half && (rounded & 1) != 0)) ++rounded;
    }
    if (rounded >= powers_of_ten[17]) {  // more digits than significand_digits holds
        std::uint32_t limbs[4];
        for (int i = 0; i < 4; ++i) limbs[i] = static_cast<std::uint32_t>(rounded >> (32 * i));
        return write_limbs_fixed(out, v < 0, limbs, 4, decimals);
    }
    auto q = static_cast<std::uint64_t>(rounded);
    if (q == 0) return *out = '0', out + 1;  // never -0
    while (decimals > 0 && q % 10 == 0) q /= 10, --decimals;
    const auto whole_number = static_cast<std::int64_t>(q);
    if (decimals == 0) return write_integer(out, v < 0 ? -whole_number : whole_number);
    if (v < 0) *out++ = '-';
    const significand_digits digits(q);
    return write_with_point(out, digits, digits.count() - decimals);
}

}  // namespace

char* write_number(char* out, double v, std::optional<int> precision) {
    // Every number keyrot prints passes here: a NaN or infinity would be a
    // bug upstream, and must stop the output rather than reach it.
    if (!std::isfinite(v)) throw std::logic_error(fmt::format("non-finite number {} in the output", v));
    if (v == 0) return *out = '0', out + 1;  // never -0; zeros are common (matrix4's constant cells)
    if (!precision) {
        // Whole numbers (frame numbers, a 4x4 matrix's 1) take the integer path.
        if (std::fabs(v) < 1e15) {
            const auto whole = static_cast<std::int64_t>(v);
            if (static_cast<double>(whole) == v) return write_integer(out, whole);
        }
        return write_shortest(out, v);
    }
    return write_fixed(out, v, *precision);
}

// Declared in io/common/layout.hpp, with how rotations are laid out, for
// everything that prints a number outside a row.
void append_number(std::string& out, double v, std::optional<int> precision) {
    char buf[max_number_chars];
    out.append(buf, static_cast<std::size_t>(write_number(buf, v, precision) - buf));
}

double shortest_decimal(float f) noexcept {
    if (!std::isfinite(f) || f == 0) return f;
    const auto decimal = fmt::detail::dragonbox::to_decimal(std::fabs(f));
    // Significand and power of ten both exact in a double: one rounding,
    // correct. Past 10^22 the powers are not: read the digits as text.
    static constexpr double powers[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                        1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    const int e = decimal.exponent;
    double v;
    if (std::abs(e) <= 22) {
        const auto significand = static_cast<double>(decimal.significand);
        v = e >= 0 ? significand * powers[e] : significand / powers[-e];
    } else {
        const std::string digits = fmt::format("{}e{}", decimal.significand, e);
        std::from_chars(digits.data(), digits.data() + digits.size(), v);
    }
    return std::signbit(f) ? -v : v;
}

}  // namespace keyrot
