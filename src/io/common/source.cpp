// SPDX-License-Identifier: MIT
#include "io/common/source.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <ctime>
#include <utility>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <streambuf>
#include <thread>

#include "ground/text.hpp"
#include "ground/thread_start.hpp"
#include "keyrot/error.hpp"

namespace keyrot {
namespace {

/// What tells a file's content changed: its size and modification time.
std::pair<off_t, std::timespec> version_of(int fd) {
    struct stat st {};
    if (::fstat(fd, &st) != 0) return {-1, {}};
    return {st.st_size, st.st_mtim};
}

/// Reads all of `size` bytes at `offset`: 0, or errno, or -1 where the file
/// ends before them.
int read_all_at(int fd, char* into, std::size_t size, off_t offset) {
    while (size > 0) {
        const ssize_t got = ::pread(fd, into, size, offset);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) return got < 0 ? errno : -1;
        into += got, size -= static_cast<std::size_t>(got), offset += got;
    }
    return 0;
}

/// Writes all of `size` bytes at `offset`, or returns false with errno set.
bool write_all_at(int fd, const char* data, std::size_t size, off_t offset) {
    while (size > 0) {
        const ssize_t put = ::pwrite(fd, data, size, offset);
        if (put < 0 && errno == EINTR) continue;
        if (put <= 0) return false;
        data += put, size -= static_cast<std::size_t>(put), offset += put;
    }
    return true;
}

}  // namespace

std::string changed_while_read(const std::string& source) {
    return fmt::format("'{}' changed while keyrot was reading it: expected it to stay as it was until keyrot is done", source);
}

/// An input that can be read only once (a pipe, standard input), copied
/// into an unlinked temporary file as the first pass reads it: later passes
/// read the copy, and what bounds a reader (a line's length) bounds the
/// copy too, so that endless input (/dev/zero) stops at the reader's limit.
struct input_source::spool {
    std::function<std::size_t(char*, std::size_t)> read_some;  // from the input; 0 at its end
    std::string path;      // of the copy, for messages
    int fd = -1;           // the copy
    off_t size = 0;        // bytes copied so far
    bool complete = false;  // the input's end was read
};

namespace {

/// Reads a file from `start` with pread, so that every stream on the same
/// descriptor has its own position: up to `end` (what the first pass
/// checked), or, for a spool, on into the input as far as it goes. A read
/// error throws keyrot::error naming `source`.
class descriptor_buffer : public std::streambuf {
public:
    descriptor_buffer(int fd, off_t start, off_t end, input_source::spool* spool, const std::string& source)
        : fd_(fd), source_(source), offset_(start), end_(end), spool_(spool) {}

protected:
    int_type underflow() override {
        if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
        if (spool_ && offset_ == spool_->size) return copied_more() ? traits_type::to_int_type(*gptr()) : traits_type::eof();
        const off_t end = spool_ ? spool_->size : end_;
        if (offset_ >= end) return traits_type::eof();  // what grew since is not what was checked
        const std::size_t got = read_at_offset(buffer_.data(), std::min(buffer_.size(), static_cast<std::size_t>(end - offset_)));
        setg(buffer_.data(), buffer_.data(), buffer_.data() + got);
        return traits_type::to_int_type(*gptr());
    }

    /// A read of more than the buffer holds (a glTF file whole) goes
    /// straight into the caller's memory: one copy, not two.
    std::streamsize xsgetn(char_type* s, std::streamsize n) override {
        std::streamsize done = std::min<std::streamsize>(n, egptr() - gptr());
        traits_type::copy(s, gptr(), static_cast<std::size_t>(done));
        setg(eback(), gptr() + done, egptr());
        if (!spool_) done += read_halves(s + done, std::min<std::streamsize>(n - done, end_ - offset_));
        for (std::size_t left; !spool_ && offset_ < end_ && (left = static_cast<std::size_t>(n - done)) > buffer_.size();)
            done += static_cast<std::streamsize>(read_at_offset(s + done, std::min(left, static_cast<std::size_t>(end_ - offset_))));
        return done + std::streambuf::xsgetn(s + done, n - done);
    }

    /// The bytes known to be left, so that a reader of the whole stream
    /// (JSON) can allocate once.
    std::streamsize showmanyc() override { return (spool_ ? spool_->size : end_) - offset_; }

private:
    /// All of `n` bytes at the file's offset, where they are 16 MiB or more:
    /// the second half on a thread of its own, so that the kernel copies
    /// them, and gives the memory they go to, on two cores at once. Returns
    /// how many were read (0 for fewer bytes, or where the system refuses
    /// the thread); the offset moves past them.
    std::streamsize read_halves(char* into, std::streamsize n) {
        constexpr std::streamsize at_least = std::streamsize{16} << 20;
        if (n < at_least) return 0;
        const std::streamsize half = n / 2;
        int second = 0;
        std::thread reader;
        if (!try_start_thread(reader, [&] {
                second = read_all_at(fd_, into + half, static_cast<std::size_t>(n - half), offset_ + half);
            }))
            return 0;
        const int first = read_all_at(fd_, into, static_cast<std::size_t>(half), offset_);
        reader.join();
        for (const int failed : {first, second})
            if (failed) throw read_failure(failed);
        offset_ += n;
        return n;
    }
    /// Up to `most` (> 0) bytes at the file's offset, which moves past them.
    std::size_t read_at_offset(char* into, std::size_t most) {
        ssize_t got;
        do got = ::pread(fd_, into, most, offset_);
        while (got < 0 && errno == EINTR);
        if (got <= 0) throw read_failure(got < 0 ? errno : -1);
        offset_ += got;
        return static_cast<std::size_t>(got);
    }
    /// What a read that failed says: `failed` is its errno, or -1 where
    /// the file ended before the bytes it held when opened (read_all_at's).
    error read_failure(int failed) const {
        return error(failed > 0 ? fmt::format("cannot read '{}': {}", source_, errno_text(failed))
                                : changed_while_read(source_));
    }
    /// More of a spooled input, read and copied; false at its end.
    bool copied_more() {
        if (spool_->complete) return false;
        const std::size_t got = spool_->read_some(buffer_.data(), buffer_.size());
        if (got == 0) return !(spool_->complete = true);
        if (!write_all_at(fd_, buffer_.data(), got, spool_->size))
            throw error(fmt::format("cannot store {} in '{}': {}", source_, spool_->path, errno_text()));
        spool_->size += static_cast<off_t>(got);
        offset_ = spool_->size;
        setg(buffer_.data(), buffer_.data(), buffer_.data() + got);
        return true;
    }

    int fd_;
    const std::string& source_;
    off_t offset_, end_;
    input_source::spool* spool_;
    std::array<char, std::size_t{1} << 16> buffer_;
};

class descriptor_stream : public std::istream {
public:
    descriptor_stream(int fd, off_t first, off_t past_end, input_source::spool* spool, const std::string& source)
        : std::istream(nullptr), buffer_(fd, first, past_end, spool, source) {
        rdbuf(&buffer_);
        exceptions(badbit);  // lets the buffer's error through istream's catch
    }

private:
    descriptor_buffer buffer_;
};

/// An unlinked temporary file for a copy of `source`, read by `read_some`.
std::unique_ptr<input_source::spool> make_spool(const std::string& source,
                                                std::function<std::size_t(char*, std::size_t)> read_some) {
    std::error_code no_directory;
    const auto directory = std::filesystem::temp_directory_path(no_directory);
    if (no_directory) {
        const char* tmpdir = std::getenv("TMPDIR");
        throw error(fmt::format("cannot store {} in a temporary file: {}{}", source,
                                tmpdir ? fmt::format("$TMPDIR '{}': ", tmpdir) : "", no_directory.message()));
    }
    auto spool = std::make_unique<input_source::spool>();
    spool->path = (directory / "keyrot-input-XXXXXX").string();
    spool->fd = ::mkostemp(spool->path.data(), O_CLOEXEC);
    if (spool->fd < 0) throw error(fmt::format("cannot store {} in '{}': {}", source, spool->path, errno_text()));
    ::unlink(spool->path.c_str());  // nothing left behind, however the process ends
    spool->read_some = std::move(read_some);
    return spool;
}

}  // namespace

input_source::input_source(const std::string& name, std::istream& stdin_stream)
    : name_(name), source_(source_name(name)) {
    if (!is_standard_stream(name)) {
        const int fd = ::open(name.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0) throw error(fmt::format("cannot read '{}': {}", name, errno_text()));
        struct stat st {};
        if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
            fd_ = fd;
            return;
        }
        // A pipe, a FIFO, process substitution, /dev/stdin, a device, or a
        // file whose size says nothing (/proc's): read once, as standard
        // input is.
        try {
            if (S_ISDIR(st.st_mode)) throw error(fmt::format("cannot read '{}': it is a directory", name));
            spool_ = make_spool(fmt::format("'{}'", name), [fd, name](char* buffer, std::size_t size) {
                ssize_t got;
                do got = ::read(fd, buffer, size);
                while (got < 0 && errno == EINTR);
                if (got < 0) throw error(fmt::format("cannot read '{}': {}", name, errno_text()));
                return static_cast<std::size_t>(got);
            });
        } catch (...) {
            ::close(fd);  // (the destructor does not run for a constructor that throws)
            throw;
        }
        input_fd_ = fd;
        fd_ = spool_->fd;
        return;
    }
    if (!stdin_stream) throw error("cannot read '<stdin>': it is closed");
    // A file on the process's standard input is read in place, from where
    // its offset stands (as cat would); anything else is spooled.
    if (&stdin_stream == &std::cin) {
        struct stat st {};
        if (::fstat(STDIN_FILENO, &st) != 0) throw error(fmt::format("cannot read '<stdin>': {}", errno_text()));
        if (S_ISDIR(st.st_mode)) throw error("cannot read '<stdin>': it is a directory");
        if (S_ISREG(st.st_mode) && st.st_size > 0) {
            start_ = ::lseek(STDIN_FILENO, 0, SEEK_CUR);
            if (start_ >= 0) fd_ = ::fcntl(STDIN_FILENO, F_DUPFD_CLOEXEC, 0);
            if (fd_ < 0) throw error(fmt::format("cannot read '<stdin>': {}", errno_text()));
            return;
        }
    }
    spool_ = make_spool("standard input", [&stdin_stream](char* buffer, std::size_t size) {
        stdin_stream.read(buffer, static_cast<std::streamsize>(size));
        return static_cast<std::size_t>(stdin_stream.gcount());
    });
    fd_ = spool_->fd;
}

input_source::~input_source() {
    ::close(fd_);
    if (input_fd_ >= 0) ::close(input_fd_);
}

std::unique_ptr<std::istream> input_source::open() const {
    if (spool_) return std::make_unique<descriptor_stream>(fd_, 0, 0, spool_.get(), source_);
    // Each pass reads what the first one checked: a file that changed in
    // between is an error before the pass that writes begins.
    const auto [size, modified] = version_of(fd_);
    if (!opened_) {
        size_ = size, modified_ = modified, opened_ = true;
    } else if (size != size_ || modified.tv_sec != modified_.tv_sec || modified.tv_nsec != modified_.tv_nsec) {
        throw error(changed_while_read(source_));
    }
    return std::make_unique<descriptor_stream>(fd_, start_, std::max(start_, size_), nullptr, source_);
}

bool input_source::is_standard_output() const {
    struct stat in {}, out {};
    return ::fstat(input_fd_ >= 0 ? input_fd_ : fd_, &in) == 0 && ::fstat(STDOUT_FILENO, &out) == 0 &&
           in.st_dev == out.st_dev && in.st_ino == out.st_ino;
}

format input_source::detect(std::optional<format> given) const {
    if (given) return *given;
    if (!is_standard_stream(name_))
        if (auto by_name = format_of_path(name_)) return *by_name;
    // The first 64 KiB decide (sniff_format needs the first line).
    std::string start(std::size_t{1} << 16, '\0');
    const auto in = open();
    in->read(start.data(), static_cast<std::streamsize>(start.size()));
    start.resize(static_cast<std::size_t>(in->gcount()));
    return sniff_format(start);
}

}  // namespace keyrot
