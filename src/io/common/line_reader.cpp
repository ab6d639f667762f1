// SPDX-License-Identifier: MIT
#include "io/common/line_reader.hpp"

#include <fmt/format.h>

#include <cstring>

#include "keyrot/error.hpp"
#include "keyrot/track.hpp"

namespace keyrot {

line_reader::line_reader(std::istream& in, std::size_t max_line, std::string source)
    : in_(in), max_line_(max_line), source_(std::move(source)), buf_(std::make_unique_for_overwrite<char[]>(size_)) {}

bool line_reader::fill() {
    if (at_end_) return false;
    if (begin_ > 0) {  // keep the unread part at the front
        std::memmove(buf_.get(), buf_.get() + begin_, end_ - begin_);
        end_ -= begin_;
        begin_ = 0;
    }
    if (end_ == size_) {  // a line longer than the buffer
        auto larger = std::make_unique_for_overwrite<char[]>(size_ * 2);
        std::memcpy(larger.get(), buf_.get(), end_);
        buf_ = std::move(larger);
        size_ *= 2;
    }
    in_.read(buf_.get() + end_, static_cast<std::streamsize>(size_ - end_));
    const auto got = static_cast<std::size_t>(in_.gcount());
    end_ += got;
    if (at_start_ && end_ >= 3) {
        if (std::string_view(buf_.get(), 3) == "\xEF\xBB\xBF") begin_ = 3;
        at_start_ = false;
    }
    if (got == 0) at_end_ = true;
    return got > 0;
}

bool line_reader::next(std::string_view& line) {
    if (held_) {
        held_ = false;
        line = last_;
        return true;
    }
    if (!read(line)) return false;
    last_ = line;
    return true;
}

bool line_reader::read(std::string_view& line) {
    std::size_t searched = begin_;
    for (;;) {
        const char* data = buf_.get();
        const void* nl = std::memchr(data + searched, '\n', end_ - searched);
        if (nl) {
            const auto eol = static_cast<std::size_t>(static_cast<const char*>(nl) - data);
            line = std::string_view(data + begin_, eol - begin_);
            begin_ = eol + 1;
            break;
        }
        const std::size_t offset = searched - begin_;
        if (end_ - begin_ > max_line_)
            throw input_error(where(source_, number_ + 1),
                              fmt::format("line longer than {} bytes: expected the lines of a keyframe table "
                                          "(--max-bytes N raises the limit)",
                                          max_line_));
        if (!fill()) {
            if (begin_ == end_) return false;
            line = std::string_view(buf_.get() + begin_, end_ - begin_);  // no final newline
            begin_ = end_;
            break;
        }
        searched = begin_ + offset;
    }
    crlf_ = !line.empty() && line.back() == '\r';
    if (crlf_) line.remove_suffix(1);
    ++number_;
    return true;
}

}  // namespace keyrot
