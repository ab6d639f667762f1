// SPDX-License-Identifier: MIT
#include "ground/text.hpp"

#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace keyrot {

std::string errno_text(int err) { return std::strerror(err); }

std::string_view trim(std::string_view text) noexcept {
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
    return text;
}

std::string ascii_lower(std::string_view text) {
    std::string out(text);
    for (char& c : out)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return out;
}

bool has_control_characters(std::string_view text) noexcept {
    for (char c : text)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return true;
    return false;
}

bool looks_like_utf16(std::string_view start) noexcept {
    // (ASCII in UTF-16 is a NUL and a letter, in one order or the other)
    return start.starts_with("\xFF\xFE") || start.starts_with("\xFE\xFF") ||
           (start.size() >= 2 && (start[0] == '\0') != (start[1] == '\0'));
}

const char* const utf16_message =
    "UTF-16 text (a spreadsheet's \"Unicode Text\", say): expected UTF-8: save it as UTF-8 (\"CSV UTF-8\"), or "
    "convert it with iconv -f UTF-16 -t UTF-8";

std::string_view without_bom(std::string_view text) noexcept {
    return text.substr(0, 3) == "\xEF\xBB\xBF" ? text.substr(3) : text;
}

std::optional<double> underflow_to_zero(std::string_view text) {
    const std::string copy(text);  // (strtod needs the terminating NUL)
    const double v = std::strtod(copy.c_str(), nullptr);
    if (v != 0) return std::nullopt;  // too large: HUGE_VAL
    return v;
}

bool is_valid_utf8(std::string_view text) noexcept {
    const auto* p = reinterpret_cast<const unsigned char*>(text.data());
    const auto* end = p + text.size();
    if (text.size() >= 8) {  // all ASCII, the common case: the high bits of all words at once, no byte loop
        std::uint64_t word, high = 0;
        for (const auto* q = p; end - q > 8; q += 8) std::memcpy(&word, q, 8), high |= word;
        std::memcpy(&word, end - 8, 8);  // the last 8 bytes, overlapping the words before
        if (((high | word) & 0x8080808080808080u) == 0) return true;
    }
    while (p < end) {
        // runs of ASCII between the other characters, eight bytes at a time
        std::uint64_t word;
        if (end - p >= 8 && (std::memcpy(&word, p, 8), (word & 0x8080808080808080u) == 0)) {
            p += 8;
            continue;
        }
        const unsigned c = *p;
        if (c < 0x80) {
            ++p;
            continue;
        }
        int extra;
        unsigned min, cp;
        if ((c & 0xE0) == 0xC0) extra = 1, min = 0x80, cp = c & 0x1F;
        else if ((c & 0xF0) == 0xE0) extra = 2, min = 0x800, cp = c & 0x0F;
        else if ((c & 0xF8) == 0xF0) extra = 3, min = 0x10000, cp = c & 0x07;
        else return false;
        if (end - p <= extra) return false;
        for (int i = 1; i <= extra; ++i) {
            if ((p[i] & 0xC0) != 0x80) return false;
            cp = (cp << 6) | (p[i] & 0x3Fu);
        }
        if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
        p += extra + 1;
    }
    return true;
}

}  // namespace keyrot
