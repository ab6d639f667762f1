// SPDX-License-Identifier: MIT
#pragma once
// Where a table's text goes: a file or a stream, a chunk at a time, each
// chunk written by a second thread while the next one fills, or batches
// formatted on other threads, written by them.
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>
#include <thread>
#include <utility>

#include "ground/thread_start.hpp"
#include "io/common/output.hpp"

namespace keyrot::detail {

/// Where output text goes: -o FILE (a temporary file renamed on success) or
/// a stream, in chunks of about a megabyte, each written by a second thread,
/// started with the first chunk and kept to the end, while the next one
/// fills (by the caller, where the system refuses that thread); or in the
/// batches formatting threads put out, each written by the thread that
/// formatted it.
class chunked_output {
public:
    chunked_output(const std::optional<std::string>& path, std::ostream& out, commit_mode commit) : out_(out) {
        if (path) file_.emplace(*path, commit);
    }
    chunked_output(const chunked_output&) = delete;
    chunked_output& operator=(const chunked_output&) = delete;
    ~chunked_output() {
        if (!writer_.joinable()) return;
        {
            const std::lock_guard lock(mutex_);
            stopping_ = true;
            changed_.notify_all();
        }
        writer_.join();  // after a write under way (an error elsewhere): it ends before the file goes
    }
    std::string& text() noexcept { return text_; }
    /// Hands text() to the writing thread once it holds a chunk.
    void maybe_flush() {
        if (text_.size() >= chunk) put();
    }
    /// Writes text(), then `text`, on this thread, and empties both (their
    /// memory kept): for batches formatted on several threads already, for
    /// which a writing thread would be one more thread to share the cores.
    /// One caller at a time.
    void write_here(std::string& text) {
        wait();
        if (!text_.empty()) {
            write(text_);
            text_.clear();
        }
        write(text);
        text.clear();
    }
    void finish() {
        wait();
        write(text_);
        if (file_) file_->commit();
    }

private:
    static constexpr std::size_t chunk = std::size_t{1} << 20;
    /// Hands text() to the writing thread, leaving it empty.
    void put() {
        wait();
        std::swap(text_, spare_);
        text_.clear();
        if (!writer_.joinable() && (unthreaded_ || !try_start_thread(writer_, [this] { write_spares(); }))) {
            unthreaded_ = true;  // no writing thread to be had: each text is written here
            return write(spare_);
        }
        const std::lock_guard lock(mutex_);
        spare_full_ = true;
        changed_.notify_all();
    }
    /// Until the writing thread is done with spare_; rethrows its error.
    void wait() {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [this] { return !spare_full_; });
        if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
    }
    void write_spares() {
        std::unique_lock lock(mutex_);
        for (;;) {
            changed_.wait(lock, [this] { return spare_full_ || stopping_; });
            if (!spare_full_) return;
            lock.unlock();
            std::exception_ptr failure;
            try {
                write(spare_);
            } catch (...) {
                failure = std::current_exception();
            }
            lock.lock();
            failure_ = failure;
            spare_full_ = false;
            changed_.notify_all();
        }
    }
    void write(const std::string& text) {
        if (file_) {
            file_->write(text);
        } else {
            write_to_stream(out_, text);
        }
    }

    std::ostream& out_;
    std::optional<output_file> file_;
    // (text_ grows as it fills, not reserved up front: mapping a megabyte
    // costs a small output more than its rows, and a large output is
    // formatted into the batches' own texts)
    std::string text_, spare_;
    std::mutex mutex_;
    std::condition_variable changed_;
    bool spare_full_ = false, stopping_ = false;  // under mutex_
    std::exception_ptr failure_;                  // under mutex_
    std::thread writer_;
    bool unthreaded_ = false;  // the system refused writer_
};

}  // namespace keyrot::detail
