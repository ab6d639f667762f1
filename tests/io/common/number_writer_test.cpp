// SPDX-License-Identifier: MIT
// Numbers as keyrot writes them: shortest round trip, or rounded as
// --precision asks, digit for digit as fmt and printf.
#include "io/common/number_writer.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

// The shortest digits come from fmt's Dragonbox (fmt::detail, an internal):
// the tests below compare keyrot's output with fmt's "{}" for fmt 9; a
// newer fmt must pass them before it is taken.
static_assert(FMT_VERSION >= 90000 && FMT_VERSION < 100000, "keyrot's number writer is checked against fmt 9");


using namespace keyrot;

namespace {
std::string number(double v, std::optional<int> precision = std::nullopt) {
    char buf[max_number_chars];
    return std::string(buf, write_number(buf, v, precision));
}
}  // namespace

TEST_CASE("numbers print in the shortest form that reads back") {
    CHECK(number(0) == "0");
    CHECK(number(-0.0) == "0");
    CHECK(number(1) == "1");
    CHECK(number(0.1) == "0.1");
    CHECK(number(1.0 / 3) == "0.3333333333333333");
    CHECK(number(0.1 + 0.2) == "0.30000000000000004");
    CHECK(number(-2.5e-300) == "-2.5e-300");
    for (double v : {std::numbers::pi, 1.0 / 7, 1e-17, 123456.789, -0.7071067811865476}) {
        CAPTURE(v);
        CHECK(std::stod(number(v)) == v);
    }
}

TEST_CASE("the shortest form is laid out exactly as fmt's \"{}\"") {
    // keyrot writes the shortest digits itself; fmt's general formatter is
    // the independent reference for the layout (fixed within 1e-4..1e16,
    // exponents with a sign and at least two digits). The digits come from
    // an internal of fmt 9 (src/io/common/number_writer.cpp pins the version).
    const auto same_as_fmt = [](double v) {
        CAPTURE(v);
        REQUIRE(number(v) == fmt::format("{}", v));
    };
    for (double v : {1e-5, 1.5e-5, 1e-4, 0.000123, 1e15, 1.5e15, 9999999999999998.0, 1e16, 1.25e16, 1e17, 1e100,
                     1.2345e-100, 5e-324, 2.2250738585072014e-308, 1.7976931348623157e308, 0.1, 123.456, -0.5})
        same_as_fmt(v);
    for (double p = 1; p < 1e18; p *= 10)  // whole numbers: the integer path up to 1e15
        for (double v : {p - 1, p, p + 1, -p, 1 - p}) same_as_fmt(v);
    // Every count of significant digits (1 to 17) with the decimal point at
    // every place before, within and after them.
    const std::string digits = "12345678901234567";
    for (std::size_t count = 1; count <= digits.size(); ++count)
        for (int point = -20; point <= 20; ++point)
            for (const char* sign : {"", "-"})
                same_as_fmt(std::stod(fmt::format("{}0.{}e{}", sign, digits.substr(0, count), point)));
    for (double v = 0; v < 1e6; ++v) same_as_fmt(v);  // frame numbers: every digit count up to 6 and its shift
    for (double v = 0; v < 1e8; v += 997) {  // every digit in every place of both 8-digit halves
        same_as_fmt(v);
        same_as_fmt(v * 1e7 + (1e8 - 1 - v));
    }
    std::mt19937_64 gen(11);
    std::uniform_int_distribution<std::uint64_t> bits;
    std::uniform_real_distribution<double> unit(-1, 1), exponent(-30, 30);
    for (int i = 0; i < 200000; ++i) {
        const double any = std::bit_cast<double>(bits(gen));  // every binary exponent
        if (std::isfinite(any) && any != 0) same_as_fmt(any);
        same_as_fmt(unit(gen));                                 // quaternion and axis components
        same_as_fmt(unit(gen) * std::pow(10.0, exponent(gen)));  // every decimal layout
        same_as_fmt(static_cast<double>(i) / 24);               // frame times
        same_as_fmt(std::trunc(unit(gen) * std::pow(10.0, exponent(gen) / 2)) + 0.0);  // whole numbers (+ 0.0: not -0)
    }
}

TEST_CASE("shortest_decimal: a float's shortest decimal, as a double") {
    // against fmt's own shortest form of the float, read back as a double
    std::mt19937 gen(24);
    std::uniform_int_distribution<std::uint32_t> bits;
    for (int i = 0; i < 200000; ++i) {
        const float f = std::bit_cast<float>(bits(gen));
        if (!std::isfinite(f)) continue;
        CAPTURE(f);
        const std::string text = fmt::format("{}", f);
        const double want = std::strtod(text.c_str(), nullptr);
        CHECK(shortest_decimal(f) == want);
        CHECK(static_cast<float>(shortest_decimal(f)) == f);
    }
    CHECK(shortest_decimal(1.0f / 30) == 0.033333335);
    CHECK(shortest_decimal(0.0f) == 0);
    CHECK(shortest_decimal(-2.5e-30f) == -2.5e-30);
}

TEST_CASE("--precision rounds and drops trailing zeros, never -0") {
    CHECK(number(0.38268343236508978, 4) == "0.3827");
    CHECK(number(0.5, 4) == "0.5");
    CHECK(number(0, 4) == "0");
    CHECK(number(-0.00001, 4) == "0");
    CHECK(number(-0.0, 2) == "0");
    CHECK(number(2.0, 0) == "2");
    CHECK(number(-1.25, 1) == "-1.2");  // round half to even on the binary value
    CHECK(number(123.0, 3) == "123");
    const std::string longest = number(-1.7976931348623157e308, 17);  // the widest number there is
    CHECK(longest.size() == 1 + 309);
    CHECK(longest.size() <= max_number_chars);
    CHECK(std::stod(longest) == -1.7976931348623157e308);
}

TEST_CASE("--precision rounds exactly as printf's \"%.Nf\" and fmt's \"{:.Nf}\"") {
    // keyrot rounds in integers; glibc's printf (exact, ties to even in the
    // default rounding mode) and fmt are two independent references.
    const auto without_trailing_zeros = [](std::string s) {
        if (s.find('.') != std::string::npos) {
            while (s.back() == '0') s.pop_back();
            if (s.back() == '.') s.pop_back();
        }
        return s == "-0" ? std::string("0") : s;
    };
    const auto same = [&](double v, int decimals) {
        CAPTURE(v);
        CAPTURE(decimals);
        char buf[400];
        const int size = std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
        const std::string ours = number(v, decimals);
        REQUIRE(ours == without_trailing_zeros(std::string(buf, static_cast<std::size_t>(size))));
        REQUIRE(ours == without_trailing_zeros(fmt::format("{:.{}f}", v, decimals)));
    };
    std::mt19937_64 gen(12);
    std::uniform_int_distribution<std::uint64_t> bits;
    for (int decimals = 0; decimals <= 17; ++decimals) {
        for (double v : {0.0, 1.0, 0.1, 1e17, 9.5e16, 99999999999999990.0, 4503599627370495.5, 4503599627370496.0,
                         9007199254740993.0, 1e-18, 5e-18, 1e-300, 5e-324, 2.2250738585072014e-308,
                         1.7976931348623157e308, 0x1.fffffffffffffp63, 0x1p64, 0x1.0000000000001p95, 0x1p128, 1e300,
                         99999.999999999985, 123456.78901234567})
            for (double s : {v, -v}) same(s, decimals);
        // Exact ties at this place (odd multiples of 2^-(N+1): to even) and their neighbours.
        for (int i = 0; i < 2000; ++i) {
            const double tie = std::ldexp(static_cast<double>(bits(gen) >> (11 + i % 53) | 1), -(decimals + 1));
            for (double v : {tie, -tie, std::nextafter(tie, 0.0), std::nextafter(tie, 1e300)}) same(v, decimals);
        }
        // Rounding up to the next power of ten, at every decimal place.
        for (int e = -17; e <= 18; ++e) {
            const double nines = std::pow(10.0, e) - std::pow(10.0, -decimals) / 2;
            for (double v : {nines, std::nextafter(nines, 0.0), std::nextafter(nines, 1e300)}) same(v, decimals);
        }
    }
    std::uniform_int_distribution<int> any_decimals(0, 17);
    std::uniform_real_distribution<double> unit(-1, 1), exponent(-20, 20);
    for (int i = 0; i < 100000; ++i) {
        const int decimals = any_decimals(gen);
        const double any = std::bit_cast<double>(bits(gen));  // every binary exponent
        if (std::isfinite(any)) same(any, decimals);
        same(unit(gen), decimals);                                  // quaternion and axis components
        same(unit(gen) * 360, decimals);                            // angles
        same(unit(gen) * std::pow(10.0, exponent(gen)), decimals);  // every decimal layout
        same(static_cast<double>(i) / 24, decimals);                // frame times
    }
}

TEST_CASE("row_text appends everything it is given, in order, past its buffer") {
    std::string out = "before;", expected = "before;";
    row_text text(out);
    const auto put = [&](std::string_view s) { text.put(s), expected += s; };
    const auto put_number = [&](double v, std::optional<int> precision) {
        text.number(v, precision), expected += number(v, precision);
    };
    const std::string name(5000, 'n');  // up to longer than the buffer
    std::mt19937_64 gen(3);
    std::uniform_int_distribution<int> what(0, 3);
    for (int i = 0; i < 400; ++i) {
        switch (what(gen)) {
            case 0: text.put(','), expected += ','; break;
            case 1: put(std::string_view(name).substr(0, static_cast<std::size_t>(i) * 13)); break;
            case 2: put_number(-1.7976931348623157e308, 17); break;  // 310 characters
            default: put_number(i / 24.0, std::nullopt); break;
        }
    }
    text.flush();
    CHECK(out.size() > 50 * 4096);
    CHECK(out == expected);
}

