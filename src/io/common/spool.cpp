// SPDX-License-Identifier: MIT
#include "io/common/spool.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

#include "ground/text.hpp"
#include "keyrot/error.hpp"

namespace keyrot {
namespace {

/// Bytes gathered in memory before they go to the file, and read back at once.
constexpr std::size_t block_bytes = std::size_t{1} << 16;

template <class Io, class Bytes>
bool whole(Io io, int fd, Bytes bytes, std::size_t size, off_t offset) {
    while (size > 0) {
        const ssize_t n = io(fd, bytes, size, offset);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        bytes += n, size -= static_cast<std::size_t>(n), offset += n;
    }
    return true;
}

}  // namespace

bool read_doubles(std::FILE* file, double* values, std::size_t count, std::size_t start) {
    return whole(::pread, ::fileno(file), reinterpret_cast<char*>(values), count * sizeof(double),
                 static_cast<off_t>(start * sizeof(double)));
}

bool write_doubles(std::FILE* file, const double* values, std::size_t count, std::size_t start) {
    return whole(::pwrite, ::fileno(file), reinterpret_cast<const char*>(values), count * sizeof(double),
                 static_cast<off_t>(start * sizeof(double)));
}

byte_spool::byte_spool() : file_(std::tmpfile()) {}

byte_spool::~byte_spool() {
    if (file_) std::fclose(file_);
}

void byte_spool::append(std::string_view bytes) {
    block_ += bytes;
    size_ += bytes.size();
    if (file_ && block_.size() >= block_bytes) flush();
}

void byte_spool::flush() {
    const auto at = static_cast<off_t>(size_ - block_.size());
    if (!whole(::pwrite, ::fileno(file_), block_.data(), block_.size(), at))
        throw error(fmt::format("cannot set output aside in a temporary file: {}", errno_text()));
    block_.clear();
}

void byte_spool::each_block(const std::function<void(std::string_view)>& f) {
    const std::size_t in_file = size_ - block_.size();
    std::string read(std::min(in_file, block_bytes), '\0');
    for (std::size_t at = 0; at < in_file; at += read.size()) {
        read.resize(std::min(block_bytes, in_file - at));
        if (!whole(::pread, ::fileno(file_), read.data(), read.size(), static_cast<off_t>(at)))
            throw error(fmt::format("cannot read back a temporary file: {}", errno_text()));
        f(read);
    }
    if (!block_.empty()) f(block_);
}

void byte_spool::read(std::size_t offset, std::size_t n, std::string& out) const {
    const std::size_t in_file = size_ - block_.size();
    out.resize(n);
    const std::size_t from_file = offset < in_file ? std::min(n, in_file - offset) : 0;
    if (from_file > 0 && !whole(::pread, ::fileno(file_), out.data(), from_file, static_cast<off_t>(offset)))
        throw error(fmt::format("cannot read back a temporary file: {}", errno_text()));
    if (from_file < n) block_.copy(out.data() + from_file, n - from_file, offset + from_file - in_file);
}

bool byte_spool::holds_at(std::size_t offset, byte_spool& other) {
    if (offset > size_ || other.size() > size_ - offset) return false;
    bool same = true;
    std::string mine;
    other.each_block([&](std::string_view block) {
        if (!same) return;
        read(offset, block.size(), mine);
        same = mine == block;
        offset += block.size();
    });
    return same;
}

}  // namespace keyrot
