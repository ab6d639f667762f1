#include "io/output.hpp"

#include <fmt/format.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <csignal>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <ostream>
#include <utility>

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

/// The descriptor a path names without opening a file: /dev/stdout,
/// /dev/stderr, /dev/fd/N, /proc/self/fd/N. Opening those would start a
/// redirected file afresh at offset 0 (`-o /dev/stdout >> log` would replace
/// the log); writing to the descriptor writes where the shell meant.
std::optional<int> descriptor_named(std::string_view path) {
    if (path == "/dev/stdin") return 0;
    if (path == "/dev/stdout") return 1;
    if (path == "/dev/stderr") return 2;
    for (std::string_view prefix : {"/dev/fd/", "/proc/self/fd/"}) {
        if (!path.starts_with(prefix)) continue;
        int fd = -1;
        const std::string_view digits = path.substr(prefix.size());
        const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), fd);
        if (ec == std::errc{} && end == digits.data() + digits.size() && fd >= 0) return fd;
    }
    return std::nullopt;
}

bool is_replaced(const std::string& path, const std::optional<struct stat>& st) {
    return !descriptor_named(path) && (!st || S_ISREG(st->st_mode));
}

/// Temporary files being written, removed by the handler of SIGINT, SIGTERM
/// and SIGHUP before the signal takes its course: fixed slots, so that the
/// handler only reads memory and calls unlink, as a handler may.
class temporaries {
public:
    static temporaries& instance() {
        static temporaries t;
        return t;
    }
    /// A slot holding `path`, or none when all are taken (the file is then
    /// left behind by a signal, as before).
    std::optional<std::size_t> add(const std::string& path) {
        if (path.size() >= PATH_MAX) return std::nullopt;
        for (std::size_t i = 0; i < slots_.size(); ++i) {
            int free = 0;
            if (!slots_[i].state.compare_exchange_strong(free, 1)) continue;
            std::memcpy(slots_[i].path, path.c_str(), path.size() + 1);
            slots_[i].state = 2;
            return i;
        }
        return std::nullopt;
    }
    void remove(std::size_t at) { slots_[at].state = 0; }

private:
    temporaries() {
        struct sigaction action {};
        action.sa_handler = on_signal;
        sigemptyset(&action.sa_mask);
        for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
            struct sigaction old {};
            // A signal the caller ignores (nohup) stays ignored.
            if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler != SIG_IGN) ::sigaction(sig, &action, nullptr);
        }
    }
    static void on_signal(int sig) {
        for (auto& taken : instance().slots_)
            if (taken.state == 2) ::unlink(taken.path);
        ::signal(sig, SIG_DFL);
        ::raise(sig);
    }
    struct path_slot {
        std::atomic<int> state{0};  // 0 free, 1 being filled, 2 holds a path
        char path[PATH_MAX];
    };
    std::array<path_slot, 64> slots_;
};

/// SIGINT, SIGTERM and SIGHUP held back on this thread while it lives.
class signals_blocked {
public:
    signals_blocked() {
        sigset_t set;
        sigemptyset(&set);
        for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&set, sig);
        ::pthread_sigmask(SIG_BLOCK, &set, &old_);
    }
    ~signals_blocked() { ::pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
    signals_blocked(const signals_blocked&) = delete;
    signals_blocked& operator=(const signals_blocked&) = delete;

private:
    sigset_t old_;
};

std::string errno_text(int err) { return std::strerror(err); }

}  // namespace

bool replaced_on_commit(const std::string& path) { return is_replaced(path, status_of(path)); }

void write_to_stream(std::ostream& out, std::string_view text) {
    if (!out) throw error("cannot write to standard output: it is closed");
    errno = 0;
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.flush();
    if (out) return;
    const int err = errno;
    throw error(err ? "cannot write to standard output: " + errno_text(err) : "cannot write to standard output");
}

output_file::output_file(std::string path) : path_(std::move(path)) {
    if (const auto fd = descriptor_named(path_)) {
        fd_ = ::fcntl(*fd, F_DUPFD_CLOEXEC, 0);
        if (fd_ < 0) fail(errno);
        return;
    }
    const auto existing = status_of(path_);
    // Through a symbolic link (or /dev/stdout redirected to a file), the
    // file it names is replaced and the link kept; another user's link is
    // refused, whatever it names (a device too).
    target_ = resolve(path_);
    if (!is_replaced(path_, existing)) {  // a device or a pipe: nothing to replace
        fd_ = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
        if (fd_ < 0) fail(errno);
        return;
    }
    if (existing) {
        // As `>` and cp do: no replacing a file one may not write (0444),
        // and no passing its set-user-ID or set-group-ID bit on.
        if (::faccessat(AT_FDCWD, target_.c_str(), W_OK, AT_EACCESS) != 0) fail(errno);
    }
    const std::filesystem::path target(target_);
    temp_ = (target.parent_path() / fmt::format(".{}.keyrot-XXXXXX", target.filename().string())).string();
    {
        // No signal between the file's creation and its registration.
        temporaries& registry = temporaries::instance();
        const signals_blocked blocked;
        fd_ = ::mkostemp(temp_.data(), O_CLOEXEC);
        if (fd_ >= 0) slot_ = registry.add(temp_);
    }
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
    ::fchmod(fd_, existing ? existing->st_mode & 0777 : 0666 & ~mask);
}

std::string output_file::resolve(const std::string& path) const {
    // A link is followed only if its owner could have written the file it
    // names anyway: the caller, or the owner of the directory it is in (the
    // kernel's protected_symlinks rule). Another user's link in a shared
    // directory would otherwise make keyrot replace a file outside it.
    std::filesystem::path at(path);
    for (int links = 0;; ++links) {
        struct stat st;
        if (::lstat(at.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return at.string();
        if (links == 40) fail(ELOOP);
        struct stat directory;
        const std::filesystem::path parent = at.has_parent_path() ? at.parent_path() : ".";
        if (st.st_uid != ::geteuid() && (::stat(parent.c_str(), &directory) != 0 || directory.st_uid != st.st_uid))
            throw error(fmt::format("cannot write '{}': '{}' is a symbolic link of another user (uid {}): expected "
                                    "a file, or a link of yours or of the directory's owner",
                                    path_, at.string(), st.st_uid));
        std::string destination(static_cast<std::size_t>(st.st_size > 0 ? st.st_size : PATH_MAX), '\0');
        const ssize_t n = ::readlink(at.c_str(), destination.data(), destination.size());
        if (n < 0) fail(errno);
        destination.resize(static_cast<std::size_t>(n));
        at = std::filesystem::path(destination).is_absolute() ? std::filesystem::path(destination) : parent / destination;
    }
}

output_file::~output_file() {
    if (fd_ >= 0) ::close(fd_);
    if (!temp_.empty()) std::remove(temp_.c_str());
    if (slot_) temporaries::instance().remove(*slot_);
}

void output_file::fail(int err) const { throw error(fmt::format("cannot write '{}': {}", path_, errno_text(err))); }

void output_file::write(std::string_view data) {
    while (!data.empty()) {
        const ssize_t n = ::write(fd_, data.data(), data.size());
        if (n < 0) {
            if (errno == EINTR) continue;
            fail(errno);
        }
        if (n == 0) fail(ENOSPC);
        data.remove_prefix(static_cast<std::size_t>(n));
        // Start writing back now, on this thread: the fsync at commit then
        // has less left to wait for.
        if (!temp_.empty()) ::sync_file_range(fd_, written_, n, SYNC_FILE_RANGE_WRITE);
        written_ += n;
    }
}

void output_file::commit() {
    const int fd = fd_;
    fd_ = -1;
    // Replacing is durable as careful tools make it: the new file's data
    // on disk before the rename, the rename on disk before success.
    if (!temp_.empty() && ::fsync(fd) != 0) {
        const int err = errno;
        ::close(fd);
        fail(err);
    }
    if (::close(fd) != 0) fail(errno);
    if (temp_.empty()) return;
    if (std::rename(temp_.c_str(), target_.c_str()) != 0) fail(errno);
    temp_.clear();
    if (slot_) temporaries::instance().remove(*std::exchange(slot_, std::nullopt));
    const std::filesystem::path parent = std::filesystem::path(target_).parent_path();
    const int directory = ::open(parent.empty() ? "." : parent.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (directory >= 0) {
        // (Some filesystems cannot sync a directory: the rename stands all the same.)
        ::fsync(directory);
        ::close(directory);
    }
}

void write_file_atomically(const std::string& path, std::string_view data) {
    output_file f(path);
    f.write(data);
    f.commit();
}

}  // namespace keyrot
