#include "keyrot/source.hpp"

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
#include <cstring>
#include <filesystem>
#include <iostream>
#include <streambuf>

#include "keyrot/error.hpp"

namespace keyrot {
namespace {

std::string errno_text() { return std::strerror(errno); }

std::string changed(const std::string& source) {
    return fmt::format("'{}' changed while keyrot was reading it: expected it to stay as it was until keyrot is done", source);
}

/// What tells a file's content changed: its size and modification time.
std::pair<off_t, std::timespec> version_of(int fd) {
    struct stat st {};
    if (::fstat(fd, &st) != 0) return {-1, {}};
    return {st.st_size, st.st_mtim};
}

/// Reads an open file from the start with pread, so that every stream on
/// the same descriptor has its own position. A read error throws
/// keyrot::error naming `source`.
class descriptor_buffer : public std::streambuf {
public:
    /// Reads [start, end) of the file.
    descriptor_buffer(int fd, off_t start, off_t end, const std::string& source)
        : fd_(fd), source_(source), offset_(start), end_(end) {}

protected:
    int_type underflow() override {
        if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
        if (offset_ >= end_) return traits_type::eof();  // what grew since is not what was checked
        ssize_t got;
        do got = ::pread(fd_, buffer_.data(), std::min<std::size_t>(buffer_.size(), static_cast<std::size_t>(end_ - offset_)), offset_);
        while (got < 0 && errno == EINTR);
        if (got < 0) throw error(fmt::format("cannot read '{}': {}", source_, errno_text()));
        if (got == 0) throw error(changed(source_));
        offset_ += got;
        setg(buffer_.data(), buffer_.data(), buffer_.data() + got);
        return traits_type::to_int_type(*gptr());
    }

    /// The bytes left in a regular file, so that a reader of the whole
    /// stream (JSON) can allocate once.
    std::streamsize showmanyc() override { return end_ - offset_; }

private:
    int fd_;
    const std::string& source_;
    off_t offset_, end_;
    std::array<char, std::size_t{1} << 16> buffer_;
};

class descriptor_stream : public std::istream {
public:
    descriptor_stream(int fd, off_t first, off_t past_end, const std::string& source)
        : std::istream(nullptr), buffer_(fd, first, past_end, source) {
        rdbuf(&buffer_);
        exceptions(badbit);  // lets the buffer's error through istream's catch
    }

private:
    descriptor_buffer buffer_;
};

/// Writes all of `size` bytes, or returns false with errno set.
bool write_all(int fd, const char* data, std::size_t size) {
    while (size > 0) {
        const ssize_t put = ::write(fd, data, size);
        if (put < 0 && errno == EINTR) continue;
        if (put <= 0) return false;
        data += put, size -= static_cast<std::size_t>(put);
    }
    return true;
}

/// A temporary file (not memory) holding what `read_some` gives until it
/// gives 0, unlinked at once so that nothing is left behind however the
/// process ends. `read_some(buffer, size)` returns the bytes read, or
/// throws keyrot::error.
template <class Read>
int spool(const std::string& source, Read&& read_some) {
    std::error_code no_directory;
    const auto directory = std::filesystem::temp_directory_path(no_directory);
    if (no_directory) {
        const char* tmpdir = std::getenv("TMPDIR");
        throw error(fmt::format("cannot store {} in a temporary file: {}{}", source,
                                tmpdir ? fmt::format("$TMPDIR '{}': ", tmpdir) : "", no_directory.message()));
    }
    std::string path = (directory / "keyrot-input-XXXXXX").string();
    const int fd = ::mkostemp(path.data(), O_CLOEXEC);
    if (fd < 0) throw error(fmt::format("cannot store {} in '{}': {}", source, path, errno_text()));
    ::unlink(path.c_str());
    std::array<char, std::size_t{1} << 16> chunk;
    try {
        while (const std::size_t got = read_some(chunk.data(), chunk.size())) {
            if (!write_all(fd, chunk.data(), got))
                throw error(fmt::format("cannot store {} in '{}': {}", source, path, errno_text()));
        }
    } catch (...) {
        ::close(fd);
        throw;
    }
    return fd;
}

}  // namespace

input_source::input_source(const std::string& name, std::istream& stdin_stream)
    : name_(name), source_(source_name(name)) {
    if (name != "-") {
        const int fd = ::open(name.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0) throw error(fmt::format("cannot read '{}': {}", name, errno_text()));
        struct stat st {};
        if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
            fd_ = fd;
            return;
        }
        // A pipe, a FIFO, process substitution, /dev/stdin, a device, or a
        // file whose size says nothing (/proc's): read once, as standard
        // input is, into a file that can be read twice.
        const bool directory = S_ISDIR(st.st_mode);
        try {
            if (directory) throw error(fmt::format("cannot read '{}': it is a directory", name));
            fd_ = spool(fmt::format("'{}'", name), [&](char* buffer, std::size_t size) {
                ssize_t got;
                do got = ::read(fd, buffer, size);
                while (got < 0 && errno == EINTR);
                if (got < 0) throw error(fmt::format("cannot read '{}': {}", name, errno_text()));
                return static_cast<std::size_t>(got);
            });
        } catch (...) {
            ::close(fd);
            throw;
        }
        ::close(fd);
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
    fd_ = spool("standard input", [&](char* buffer, std::size_t size) {
        stdin_stream.read(buffer, static_cast<std::streamsize>(size));
        return static_cast<std::size_t>(stdin_stream.gcount());
    });
}

input_source::~input_source() { ::close(fd_); }

std::unique_ptr<std::istream> input_source::open() const {
    // Each pass reads what the first one checked: a file that changed in
    // between is an error before the pass that writes begins.
    const auto [size, modified] = version_of(fd_);
    if (!opened_) {
        size_ = size, modified_ = modified, opened_ = true;
    } else if (size != size_ || modified.tv_sec != modified_.tv_sec || modified.tv_nsec != modified_.tv_nsec) {
        throw error(changed(source_));
    }
    return std::make_unique<descriptor_stream>(fd_, start_, std::max(start_, size_), source_);
}

format input_source::detect(std::optional<format> given) const {
    if (given) return *given;
    if (name_ != "-")
        if (auto by_name = format_of_path(name_)) return *by_name;
    // The first 64 KiB decide (sniff_format needs the first line).
    std::string start(std::size_t{1} << 16, '\0');
    const auto in = open();
    in->read(start.data(), static_cast<std::streamsize>(start.size()));
    start.resize(static_cast<std::size_t>(in->gcount()));
    return sniff_format(start);
}

}  // namespace keyrot
