// SPDX-License-Identifier: MIT
#pragma once
// Internal: keyrot's threads only make it faster. Where the system refuses
// one (a limit on processes, or on address space, from which each thread's
// stack is taken), the work is done on the threads there are, or on the
// caller's, with the same result.
#include <new>
#include <system_error>
#include <thread>
#include <utility>

namespace keyrot {

/// `f` on a new thread, put in `t`; false, and `t` untouched, where the
/// system refuses the thread.
template <class F>
bool try_start_thread(std::thread& t, F&& f) {
    try {
        t = std::thread(std::forward<F>(f));
        return true;
    } catch (const std::system_error&) {
        return false;
    } catch (const std::bad_alloc&) {
        return false;
    }
}

}  // namespace keyrot
