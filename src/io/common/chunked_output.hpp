#pragma once
// Where a table's text goes: a file or a stream, a chunk at a time, each
// chunk written by a second thread while the next one fills.
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
/// a stream, in chunks of about a megabyte or in the batches formatting
/// threads put out. Each is written by a second thread, started with the
/// first chunk and kept to the end, while the next one fills (by the
/// caller, where the system refuses that thread).
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
    /// Room for `bytes` in the buffer put() gives in exchange for the first
    /// text it takes (the texts put out then go round, never shrinking).
    void reserve_exchange(std::size_t bytes) { spare_.reserve(bytes); }
    void maybe_flush() {
        if (text_.size() >= chunk) put(text_);
    }
    /// Puts out `text` after text(), which it leaves empty, and gives it an
    /// empty buffer in exchange: a batch formatted elsewhere is not copied.
    /// One caller at a time.
    void put(std::string& text) {
        wait();
        if (&text != &text_ && !text_.empty()) {
            write(text_);
            text_.clear();
        }
        std::swap(text, spare_);
        text.clear();
        if (!writer_.joinable() && (unthreaded_ || !try_start_thread(writer_, [this] { write_spares(); }))) {
            unthreaded_ = true;  // no writing thread to be had: each text is written here
            return write(spare_);
        }
        const std::lock_guard lock(mutex_);
        spare_full_ = true;
        changed_.notify_all();
    }
    void finish() {
        wait();
        write(text_);
        if (file_) file_->commit();
    }

private:
    static constexpr std::size_t chunk = std::size_t{1} << 20;
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
