// SPDX-License-Identifier: MIT
#pragma once
// Bytes set aside in a temporary file, so that memory does not grow with
// them: an output's data gathered before the header that must come first,
// a take's columns, a BVH output's rows.
#include <cstdio>
#include <functional>
#include <string>
#include <string_view>

namespace keyrot {

/// `count` doubles at double index `start` of `file`, read or written
/// whole. False on an error (errno says which).
bool read_doubles(std::FILE* file, double* values, std::size_t count, std::size_t start);
bool write_doubles(std::FILE* file, const double* values, std::size_t count, std::size_t start);

/// Bytes appended in order and read back in order: in a temporary file, a
/// block at a time (in memory where the system gives no temporary file).
/// Throws keyrot::error when the file cannot be written or read.
///
///     byte_spool s;
///     s.append("abc");
///     s.each_block([](std::string_view b) { /* "abc" */ });
class byte_spool {
public:
    byte_spool();
    byte_spool(const byte_spool&) = delete;
    byte_spool& operator=(const byte_spool&) = delete;
    ~byte_spool();
    void append(std::string_view bytes);
    std::size_t size() const noexcept { return size_; }
    /// Empty again (the file kept, to be written over).
    void clear() noexcept { size_ = 0, block_.clear(); }
    /// Calls `f` with the bytes, in order, a block at a time.
    void each_block(const std::function<void(std::string_view)>& f);
    /// Whether the bytes from `offset` on begin with those of `other`.
    bool holds_at(std::size_t offset, byte_spool& other);

private:
    void flush();
    /// `n` bytes from `offset` (within size()) into `out`.
    void read(std::size_t offset, std::size_t n, std::string& out) const;

    std::FILE* file_;
    std::string block_;      // the bytes after the file's: all of them without a file
    std::size_t size_ = 0;   // in all
};

}  // namespace keyrot
