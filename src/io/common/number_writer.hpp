// SPDX-License-Identifier: MIT
#pragma once
// Numbers as text, fast: every number keyrot writes passes here, millions
// of them for a large output (docs/design.md says why not fmt's own).
#include <algorithm>
#include <cstddef>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>

namespace keyrot {

/// Writes v at `out` (room for max_number_chars) in the shortest form that
/// reads back to the same double, or rounded to `precision` decimals without
/// trailing zeros; returns the end. Never "-0". Throws std::logic_error for
/// NaN or infinity (a bug, never printed).
char* write_number(char* out, double v, std::optional<int> precision);
inline constexpr std::size_t max_number_chars = 330;  // "{:.17f}" of -1.8e308 has 327

/// The double nearest the shortest decimal that reads back as `f` (what a
/// 32-bit float written as text reads back as): 0.033333335 for the float
/// nearest 1/30, where the float itself is 0.03333333507180214.
double shortest_decimal(float f) noexcept;

/// The text of an output row, gathered on the stack and appended to `out`
/// in large pieces: appending to a std::string piece by piece costs more
/// than printing the numbers. Call flush() at the end of the row.
class row_text {
public:
    explicit row_text(std::string& out) noexcept : out_(out) {}
    row_text(const row_text&) = delete;
    row_text& operator=(const row_text&) = delete;

    void put(char c) {
        if (end_ == std::end(buf_)) flush();
        *end_++ = c;
    }
    void put(std::string_view text) {
        if (text.size() > room()) {
            flush();
            if (text.size() > room()) return (void)out_.append(text);
        }
        end_ = std::copy(text.begin(), text.end(), end_);
    }
    void number(double v, std::optional<int> precision) {
        if (room() < max_number_chars) flush();
        end_ = write_number(end_, v, precision);
    }
    void flush() {
        out_.append(buf_, static_cast<std::size_t>(end_ - buf_));  // (pointer, length): not the iterator overload
        end_ = buf_;
    }

private:
    std::size_t room() const noexcept { return static_cast<std::size_t>(std::end(buf_) - end_); }

    std::string& out_;
    char buf_[4096];
    char* end_ = buf_;
};

}  // namespace keyrot
