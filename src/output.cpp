#include "keyrot/output.hpp"

#include <fmt/format.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "keyrot/error.hpp"

namespace keyrot {

output_file::output_file(std::string path) : path_(std::move(path)) {
    const std::filesystem::path target(path_);
    temp_ = (target.parent_path() / fmt::format(".{}.keyrot-XXXXXX", target.filename().string())).string();
    fd_ = ::mkstemp(temp_.data());
    if (fd_ < 0) {
        temp_.clear();
        fail(errno);
    }
    // mkstemp creates the file 0600; give it the usual permissions. umask
    // can only be read by setting it: once, before --jobs threads could race.
    static const mode_t mask = [] {
        const mode_t m = ::umask(0);
        ::umask(m);
        return m;
    }();
    ::fchmod(fd_, 0666 & ~mask);
}

output_file::~output_file() {
    if (fd_ >= 0) ::close(fd_);
    if (!temp_.empty()) std::remove(temp_.c_str());
}

void output_file::fail(int err) { throw error(fmt::format("cannot write '{}': {}", path_, std::strerror(err))); }

void output_file::write(std::string_view data) {
    while (!data.empty()) {
        const ssize_t n = ::write(fd_, data.data(), data.size());
        if (n < 0) {
            if (errno == EINTR) continue;
            fail(errno);
        }
        data.remove_prefix(static_cast<std::size_t>(n));
        // Start writing back now, on this thread: renaming over an existing
        // file makes ext4 write back all that is left at commit, alone.
        ::sync_file_range(fd_, written_, n, SYNC_FILE_RANGE_WRITE);
        written_ += n;
    }
}

void output_file::commit() {
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0 || std::rename(temp_.c_str(), path_.c_str()) != 0) fail(errno);
    temp_.clear();
}

void write_file_atomically(const std::string& path, std::string_view data) {
    output_file f(path);
    f.write(data);
    f.commit();
}

}  // namespace keyrot
