#pragma once
// How rotations are laid out in files, shared by every reader and writer:
// quaternion order, the CSV columns of each representation, the values
// written for a rotation, and how numbers are printed.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <istream>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "ground/text.hpp"
#include "keyrot/convert.hpp"
#include "keyrot/quat.hpp"

namespace keyrot {

/// CSV columns of a representation's rotation, in output order:
/// rotation_columns(rep::axis_angle, ...) = {"ax", "ay", "az", "angle"}.
/// For rep::matrix4 these are m00..m33 (translation included).
std::span<const std::string_view> rotation_columns(rep r, quat_order order) noexcept;
inline constexpr std::array<std::string_view, 3> translation_columns = {"tx", "ty", "tz"};

/// Reorder 4 values between file order and (w, x, y, z).
std::array<double, 4> from_quat_order(std::array<double, 4> v, quat_order order) noexcept;

struct write_options {
    rep representation = rep::axis_angle;
    std::optional<euler_seq> euler;  ///< required for rep::euler
    angle_unit angles = angle_unit::degrees;
    quat_order order = quat_order::wxyz;
    std::optional<int> precision;  ///< digits after the point; none = shortest round trip
};

/// A rotation's values in column order, angles in the output unit.
struct rotation_values {
    std::array<double, 16> v{};
    std::size_t size = 0;
    bool gimbal_lock = false;
};
/// `translation` is used by rep::matrix4 only (zero when absent).
rotation_values values_of(quat q, const std::optional<vec3>& translation, const write_options& opts);

/// Writes v at `out` (room for max_number_chars) in the shortest form that
/// reads back to the same double, or rounded to `precision` decimals without
/// trailing zeros; returns the end. Never "-0". Throws std::logic_error for
/// NaN or infinity (a bug, never printed).
char* write_number(char* out, double v, std::optional<int> precision);
inline constexpr std::size_t max_number_chars = 330;  // "{:.17f}" of -1.8e308 has 327
/// write_number, appended to `out`.
void append_number(std::string& out, double v, std::optional<int> precision);

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

/// Reads a stream line by line in large chunks, for the line-based readers:
/// '\n' ends a line, a '\r' before it is dropped, and a UTF-8 byte-order
/// mark at the start is skipped. A line may be longer than a chunk, but not
/// than `max_line` bytes: next() then throws input_error naming `source`
/// and the line.
class line_reader {
public:
    line_reader(std::istream& in, std::size_t max_line, std::string source);
    /// The next line (valid until the next call), or false at the end.
    /// number() is its 1-based number.
    bool next(std::string_view& line);
    std::size_t number() const noexcept { return number_; }

private:
    bool fill();  // reads more; false at the end of the stream

    std::istream& in_;
    std::size_t max_line_;
    std::string source_;
    std::string buf_;
    std::size_t begin_ = 0, end_ = 0;  // unread bytes in buf_
    std::size_t number_ = 0;
    bool at_start_ = true, at_end_ = false;
};

}  // namespace keyrot
