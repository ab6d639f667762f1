// SPDX-License-Identifier: MIT
#include "io/common/output.hpp"

#include <fmt/format.h>
#include <fcntl.h>
#include <stdio_ext.h>
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
#include <iostream>
#include <memory>
#include <optional>
#include <ostream>
#include <set>
#include <utility>

#include "ground/text.hpp"
#include "io/common/file_release.hpp"
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

/// Temporary files being written (or waiting for a durable batch), removed
/// by the handler of SIGINT, SIGTERM and SIGHUP before the signal takes its
/// course: slots in blocks that are added as needed and never freed, so
/// that the handler only reads memory and calls unlink, as a handler may.
class temporaries {
public:
    static temporaries& instance() {
        static temporaries t;
        return t;
    }
    /// A slot holding `path`, or none for a path too long to hold (the file
    /// is then left behind by a signal).
    std::optional<std::size_t> add(const std::string& path) {
        if (path.size() >= PATH_MAX) return std::nullopt;
        std::size_t first = 0;
        for (block* b = &first_;; b = next_of(*b), first += block_slots) {
            for (std::size_t i = 0; i < block_slots; ++i) {
                int free = 0;
                if (!b->states[i].compare_exchange_strong(free, 1)) continue;
                std::memcpy(b->paths[i].data(), path.c_str(), path.size() + 1);
                b->states[i] = 2;
                return first + i;
            }
        }
    }
    void remove(std::size_t at) {
        block* b = &first_;
        for (; at >= block_slots; at -= block_slots) b = b->next.load();
        b->states[at] = 0;
    }

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
        for (const block* b = &instance().first_; b; b = b->next.load())
            for (std::size_t i = 0; i < block_slots; ++i)
                if (b->states[i] == 2) ::unlink(b->paths[i].data());
        ::signal(sig, SIG_DFL);
        ::raise(sig);
    }
    static constexpr std::size_t block_slots = 64;
    // The states side by side and the paths apart: setting up the registry
    // then touches one page, not one a slot (a page fault each, at every
    // start-up that writes a file).
    struct block {
        std::array<std::atomic<int>, block_slots> states{};  // 0 free, 1 being filled, 2 holds a path
        std::array<std::array<char, PATH_MAX>, block_slots> paths;
        std::atomic<block*> next{nullptr};
    };
    /// The block after `b`, added if there is none yet.
    static block* next_of(block& b) {
        block* next = b.next.load();
        if (next) return next;
        auto fresh = std::make_unique<block>();
        if (b.next.compare_exchange_strong(next, fresh.get())) return fresh.release();
        return next;  // another thread added one
    }
    block first_;
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

std::string cannot_write(const std::string& path, int err) {
    return fmt::format("cannot write '{}': {}", path, errno_text(err));
}

std::string parent_of(const std::string& path) {
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    return parent.empty() ? "." : parent.string();
}

/// Puts the file at `temp` in `target`'s place at once: a reader finds the
/// old file or the new one, never neither. A regular file at `target` is
/// exchanged with it (renameat2's RENAME_EXCHANGE), then removed from
/// `temp`, rather than renamed over: ext4 (auto_da_alloc) writes a file
/// renamed over another back to disk inside the rename, most of the tail
/// of a large output's run, and its space is freed without keyrot waiting
/// for it. Durability is --fsync's. Anything else at `target`, none, or a
/// filesystem that cannot exchange: a rename. Returns false, errno set,
/// where the file could not be put in place.
bool put_in_place(const std::string& temp, const std::string& target) {
    struct stat st;
    if (::lstat(target.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
        ::renameat2(AT_FDCWD, temp.c_str(), AT_FDCWD, target.c_str(), RENAME_EXCHANGE) == 0) {
        remove_replaced(temp, st.st_size);  // (the old file, now at temp)
        return true;
    }
    return std::rename(temp.c_str(), target.c_str()) == 0;
}

/// Makes a rename in `directory` durable. (Some filesystems cannot sync a
/// directory: the rename stands all the same.)
void sync_directory(const std::string& directory) {
    const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    ::fsync(fd);
    ::close(fd);
}

}  // namespace

bool replaced_on_commit(const std::string& path) { return is_replaced(path, status_of(path)); }

std::optional<standard_output_mark> standard_output_mark::of(std::ostream& out) {
    if (&out != &std::cout || !out.flush()) return std::nullopt;
    struct stat st {}, err {};
    const int flags = ::fcntl(STDOUT_FILENO, F_GETFL);
    if (flags < 0 || (flags & O_APPEND) != 0 || ::fstat(STDOUT_FILENO, &st) != 0 || !S_ISREG(st.st_mode))
        return std::nullopt;
    if (::fstat(STDERR_FILENO, &err) == 0 && err.st_dev == st.st_dev && err.st_ino == st.st_ino) return std::nullopt;
    const off_t at = ::lseek(STDOUT_FILENO, 0, SEEK_CUR);
    // (cutting it where it ends changes nothing, where it may be cut at all)
    if (at != st.st_size || ::ftruncate(STDOUT_FILENO, at) != 0) return std::nullopt;
    return standard_output_mark(at);
}

void standard_output_mark::take_back(std::ostream& out) const {
    // std::cout writes through stdio's stdout: what it holds came after the
    // mark (flushed then), and must not follow the cut.
    ::__fpurge(stdout);
    out.clear();
    if (::ftruncate(STDOUT_FILENO, at_) != 0 || ::lseek(STDOUT_FILENO, at_, SEEK_SET) != at_)
        throw error("cannot take back what was written to standard output: " + errno_text());
}

void write_to_stream(std::ostream& out, std::string_view text) {
    if (!out) throw error("cannot write to standard output: it is closed");
    errno = 0;
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.flush();
    if (out) return;
    const int err = errno;
    throw error(err ? "cannot write to standard output: " + errno_text(err) : "cannot write to standard output");
}

output_file::output_file(std::string path, commit_mode mode) : path_(std::move(path)), mode_(mode) {
    if (const auto fd = descriptor_named(path_)) {
        fd_ = ::fcntl(*fd, F_DUPFD_CLOEXEC, 0);
        if (fd_ < 0) fail(errno);
        return;
    }
    // Through a symbolic link (or /dev/stdout redirected to a file), the
    // file it names is replaced and the link kept; another user's link is
    // refused, whatever it names (a device too). Where links are not
    // followed, only a regular file at the name is a file to replace as
    // such: anything else there (a link, a FIFO) is renamed over.
    std::optional<struct stat> existing = status_of(path_);
    if (!mode_.follow_links) {
        struct stat st;
        if (::lstat(path_.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) existing.reset();
        else existing = st;
    }
    target_ = mode_.follow_links ? resolve(path_) : path_;
    if (mode_.follow_links && !is_replaced(path_, existing)) {  // a device or a pipe: nothing to replace
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
    // Root keeps the owner and group of the file it replaces (chown before
    // chmod, which chown would otherwise undo in part).
    if (existing && ::geteuid() == 0 && ::fchown(fd_, existing->st_uid, existing->st_gid) != 0) fail(errno);
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

void output_file::fail(int err) const { throw error(cannot_write(path_, err)); }

void output_file::write(std::string_view data) {
    while (!data.empty()) {
        const ssize_t n = ::write(fd_, data.data(), data.size());
        if (n < 0) {
            if (errno == EINTR) continue;
            fail(errno);
        }
        if (n == 0) fail(ENOSPC);
        data.remove_prefix(static_cast<std::size_t>(n));
        // Durable: start writing back now, on this thread, so that the sync
        // at commit has less left to wait for.
        if (!temp_.empty() && mode_.fsync) ::sync_file_range(fd_, written_, n, SYNC_FILE_RANGE_WRITE);
        written_ += n;
    }
}

void output_file::commit() {
    const int fd = std::exchange(fd_, -1);
    // Durable as careful tools make it: the new file's data on disk before
    // the rename, the rename on disk before success (a batch does both for
    // all its files at once).
    const bool sync_here = mode_.fsync && !mode_.batch;
    if (!temp_.empty() && sync_here && ::fsync(fd) != 0) {
        const int err = errno;
        ::close(fd);
        fail(err);
    }
    if (::close(fd) != 0) fail(errno);
    if (temp_.empty()) return;
    if (mode_.fsync && mode_.batch) {
        mode_.batch->add({path_, std::exchange(temp_, {}), target_, std::exchange(slot_, std::nullopt)});
        return;
    }
    if (!put_in_place(temp_, target_)) fail(errno);
    temp_.clear();
    if (slot_) temporaries::instance().remove(*std::exchange(slot_, std::nullopt));
    if (sync_here) sync_directory(parent_of(target_));
}

void write_file_atomically(const std::string& path, std::string_view data, commit_mode mode) {
    output_file f(path, mode);
    f.write(data);
    f.commit();
}

void durable_batch::add(pending file) {
    const std::lock_guard lock(mutex_);
    files_.push_back(std::move(file));
}

void durable_batch::finish() {
    std::vector<pending> files;
    {
        const std::lock_guard lock(mutex_);
        files.swap(files_);
    }
    std::optional<std::string> failure;
    // The data of every file on disk, one sync per filesystem, before any rename.
    std::set<std::string> directories;
    for (const pending& f : files) directories.insert(parent_of(f.target));
    std::set<dev_t> synced;
    for (const std::string& directory : directories) {
        const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        struct stat st {};
        const bool opened = fd >= 0 && ::fstat(fd, &st) == 0;
        if (opened && synced.insert(st.st_dev).second && ::syncfs(fd) != 0 && !failure) failure = cannot_write(directory, errno);
        if (fd >= 0) ::close(fd);
    }
    if (failure) {
        files_.swap(files);  // removed by the destructor
        throw error(*failure);
    }
    for (pending& f : files) {
        if (!put_in_place(f.temp, f.target)) {
            if (!failure) failure = cannot_write(f.path, errno);
            std::remove(f.temp.c_str());
        }
        if (f.slot) temporaries::instance().remove(*f.slot);
    }
    for (const std::string& directory : directories) sync_directory(directory);
    if (failure) throw error(*failure);
}

durable_batch::~durable_batch() {
    for (const pending& f : files_) {
        std::remove(f.temp.c_str());
        if (f.slot) temporaries::instance().remove(*f.slot);
    }
}

}  // namespace keyrot
