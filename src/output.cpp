#include "keyrot/output.hpp"

#include <fmt/format.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>

#include "keyrot/error.hpp"

namespace keyrot {
namespace {

/// What stat(2) says of `path` (through symbolic links); nothing when there
/// is no such file, or it cannot be looked at (writing it will then say why).
std::optional<struct stat> status_of(const std::string& path) {
    struct stat st;
    if (::stat(path.c_str(), &st) != 0) return std::nullopt;
    return st;
}

bool is_replaced(const std::optional<struct stat>& st) { return !st || S_ISREG(st->st_mode); }

}  // namespace

bool replaced_on_commit(const std::string& path) { return is_replaced(status_of(path)); }

output_file::output_file(std::string path) : path_(std::move(path)) {
    const auto existing = status_of(path_);
    if (!is_replaced(existing)) {  // a device or a pipe: nothing to replace
        fd_ = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
        if (fd_ < 0) fail(errno);
        return;
    }
    // Through a symbolic link (or /dev/stdout redirected to a file), the
    // file it names is replaced and the link kept.
    std::filesystem::path target(path_);
    if (existing) {
        char resolved[PATH_MAX];
        if (::realpath(path_.c_str(), resolved)) target = resolved;
    }
    target_ = target.string();
    temp_ = (target.parent_path() / fmt::format(".{}.keyrot-XXXXXX", target.filename().string())).string();
    fd_ = ::mkostemp(temp_.data(), O_CLOEXEC);
    if (fd_ < 0) {
        temp_.clear();
        fail(errno);
    }
    // mkstemp creates the file 0600: give it the mode of the file it
    // replaces, or the usual one. umask can only be read by setting it:
    // once, before --jobs threads could race.
    static const mode_t mask = [] {
        const mode_t m = ::umask(0);
        ::umask(m);
        return m;
    }();
    ::fchmod(fd_, existing ? existing->st_mode & 07777 : 0666 & ~mask);
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
        if (!temp_.empty()) ::sync_file_range(fd_, written_, n, SYNC_FILE_RANGE_WRITE);
        written_ += n;
    }
}

void output_file::commit() {
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail(errno);
    if (temp_.empty()) return;
    if (std::rename(temp_.c_str(), target_.c_str()) != 0) fail(errno);
    temp_.clear();
}

void write_file_atomically(const std::string& path, std::string_view data) {
    output_file f(path);
    f.write(data);
    f.commit();
}

}  // namespace keyrot
