// SPDX-License-Identifier: MIT
#pragma once
// Text, on the ground floor with the errors: UTF-8, trimming, and numbers
// as CSV cells and the command line write them; the text of a system error.
#include <cerrno>
#include <charconv>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>

namespace keyrot {

/// What the system says error `err` is ("No such file or directory").
std::string errno_text(int err = errno);

/// True if `text` is well-formed UTF-8 (no overlong forms, no surrogates).
bool is_valid_utf8(std::string_view text) noexcept;
/// True if `text` has control characters (below 0x20, or 0x7f).
bool has_control_characters(std::string_view text) noexcept;

/// Whether `start`, the beginning of a file that is not UTF-8, is UTF-16
/// (a spreadsheet's "Unicode Text"): a UTF-16 byte-order mark, or a
/// character and a NUL byte (which no text keyrot reads holds), in either
/// order.
bool looks_like_utf16(std::string_view start) noexcept;
/// What keyrot says of a UTF-16 file: "UTF-16 text (...): expected UTF-8 ...".
extern const char* const utf16_message;

/// `text` without a leading UTF-8 byte-order mark.
std::string_view without_bom(std::string_view text) noexcept;
/// `text` without leading and trailing spaces and tabs.
std::string_view trim(std::string_view text) noexcept;
/// `text` with ASCII letters in lower case.
std::string ascii_lower(std::string_view text);

/// A number too small for a double (1e-400) read as the nearest, zero with
/// its sign, as the JSON readers read it; nothing for one too large.
std::optional<double> underflow_to_zero(std::string_view text);

/// A number as written in CSV cells and on the command line: optional
/// surrounding spaces, an optional '+', then what std::from_chars reads.
/// std::nullopt unless the whole text is one finite double (one too small
/// for a double is 0). Inline: GCC returns an optional<double> through
/// memory, and reading its flag back stalls the caller (a tenth of the
/// time spent parsing a CSV).
inline std::optional<double> parse_number(std::string_view text) {
    text = trim(text);
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    if (text.empty() || text.front() == '+' || text.front() == ' ') return std::nullopt;
    double v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (end != text.data() + text.size()) return std::nullopt;
    if (ec == std::errc::result_out_of_range) return underflow_to_zero(text);
    if (ec != std::errc{} || !std::isfinite(v)) return std::nullopt;
    return v;
}

}  // namespace keyrot
