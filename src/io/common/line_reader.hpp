// SPDX-License-Identifier: MIT
#pragma once
// Lines of a stream, for the line-based readers.
#include <cstddef>
#include <istream>
#include <memory>
#include <string>
#include <string_view>

namespace keyrot {

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
    /// The line read last ended in "\r\n" (the '\r' dropped).
    bool crlf() const noexcept { return crlf_; }
    /// The next call of next() gives the line it gave last once more, with
    /// its number: a line read to learn what it is (a header, or the first
    /// key), then read as a key.
    void put_back() noexcept { held_ = true; }

private:
    bool read(std::string_view& line);  // the next line from the stream
    bool fill();                        // reads more; false at the end of the stream

    std::istream& in_;
    std::size_t max_line_;
    std::string source_;
    std::size_t size_ = std::size_t{1} << 16;
    std::unique_ptr<char[]> buf_;      // of size_ bytes, not zeroed: only what was read is read
    std::size_t begin_ = 0, end_ = 0;  // unread bytes in buf_
    std::size_t number_ = 0;
    bool at_start_ = true, at_end_ = false, crlf_ = false;
    std::string_view last_;  // the line next() gave last
    bool held_ = false;      // put back: next() gives last_ again
};

}  // namespace keyrot
