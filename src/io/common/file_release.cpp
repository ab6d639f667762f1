// SPDX-License-Identifier: MIT
#include "io/common/file_release.hpp"

#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstddef>

namespace keyrot {
namespace {

// Below this, unlinking costs less than starting a process.
constexpr off_t worth_a_process = off_t{4} << 20;

/// Where a holder runs: the process that keeps the last reference to a
/// removed file until keyrot has closed its own, then ends, and the kernel
/// frees the file's blocks in its exit. Holders share keyrot's memory
/// (CLONE_VM: nothing to copy), so each place has a stack, mapped when
/// first used and used again only once the kernel has cleared `running` at
/// the holder's end (CLONE_CHILD_CLEARTID). Holders signal no one at their
/// end: keyrot reaps one when it uses its place again, and init those
/// keyrot leaves. (Zeros at first, with no initialiser: a run that
/// replaces no large file touches none of this.)
struct holder {
    pid_t running;  // nonzero while a holder runs here
    pid_t pid;      // the holder to reap, if any
    int file, gate;
    std::byte* stack;
};
constexpr std::size_t stack_bytes = 64 * 1024;
std::array<holder, 4> holders;

/// `h` free for another holder (none started in it, or the claim undone).
void free_place(holder& h) noexcept { std::atomic_ref<pid_t>(h.running).store(0); }

holder* claim_holder() noexcept {
    for (holder& h : holders) {
        pid_t ended = 0;
        if (!std::atomic_ref<pid_t>(h.running).compare_exchange_strong(ended, -1)) continue;
        if (h.pid > 0) ::waitpid(h.pid, nullptr, static_cast<int>(__WCLONE));
        h.pid = 0;
        if (!h.stack) {
            void* stack = ::mmap(nullptr, stack_bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_STACK,
                                 -1, 0);
            if (stack != MAP_FAILED) h.stack = static_cast<std::byte*>(stack);
        }
        if (h.stack) return &h;
        free_place(h);
        return nullptr;
    }
    return nullptr;
}

/// The holder. It runs beside keyrot's own thread, on that thread's
/// thread-local storage: raw system calls only, none of which can fail and
/// set errno. Its signals are blocked (keyrot's handlers are not its own);
/// it ends when the gate closes, or is killed.
int hold(void* arg) {
    const auto& h = *static_cast<const holder*>(arg);
    const auto low = static_cast<unsigned>(std::min(h.file, h.gate));
    const auto high = static_cast<unsigned>(std::max(h.file, h.gate));
    // The file and the gate's reading end only: a copy of standard output
    // kept open would keep a pipeline waiting for its end.
    if (low > 0) ::syscall(SYS_close_range, 0U, low - 1, 0U);
    if (high > low + 1) ::syscall(SYS_close_range, low + 1, high - 1, 0U);
    ::syscall(SYS_close_range, high + 1, ~0U, 0U);
    char byte;
    ::syscall(SYS_read, h.gate, &byte, 1);  // returns at the end of the gate: keyrot has closed the file
    return 0;
}

/// Hands the file open at `file` to a holder; false where none could start.
bool hand_over(int file) noexcept {
    holder* h = claim_holder();
    int gate[2];
    if (!h) return false;
    if (::pipe2(gate, O_CLOEXEC) != 0) {
        free_place(*h);
        return false;
    }
    h->file = file, h->gate = gate[0];
    sigset_t all, old;
    ::sigfillset(&all);
    ::pthread_sigmask(SIG_SETMASK, &all, &old);
    h->pid = ::clone(hold, h->stack + stack_bytes, CLONE_VM | CLONE_CHILD_CLEARTID, h, nullptr, nullptr, &h->running);
    ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
    const bool started = h->pid > 0;
    if (!started) free_place(*h);
    ::close(gate[0]);
    if (started) ::close(file);  // before the gate: the holder's reference is to be the last
    ::close(gate[1]);
    return started;
}

}  // namespace

void remove_replaced(const std::string& path, off_t size) noexcept {
    const int file = size < worth_a_process ? -1 : ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    ::unlink(path.c_str());
    if (file >= 0 && !hand_over(file)) ::close(file);
}

}  // namespace keyrot
