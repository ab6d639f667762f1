#pragma once
// Bytes set aside in a temporary file, so that memory does not grow with
// them: an output's data gathered before the header that must come first,
// a take's columns read back one at a time.
#include <sys/types.h>

#include <cstdio>
#include <functional>
#include <string>
#include <string_view>

namespace keyrot {

/// pread or pwrite of `size` bytes at `offset` of `fd`, whole (again after
/// a signal, and after a short count). False on an error (errno says which).
bool transfer_whole(ssize_t (*io)(int, void*, std::size_t, off_t), int fd, char* bytes, std::size_t size, off_t offset);
bool transfer_whole(ssize_t (*io)(int, const void*, std::size_t, off_t), int fd, const char* bytes, std::size_t size,
                    off_t offset);

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

private:
    void flush();

    std::FILE* file_;
    std::string block_;      // the bytes after the file's: all of them without a file
    std::size_t size_ = 0;   // in all
};

}  // namespace keyrot
