#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>

#include "keyrot/io.hpp"

namespace keyrot {
namespace {

/// Parses keys on a thread of its own, batches ahead of the caller, so that
/// reading a long input overlaps with what the caller does with its keys.
/// The first keys are read on the caller's thread: a small input never
/// starts the thread, nor one where worth_it() then says no. What the inner
/// reader throws comes out of next() after the keys before it, as it would
/// without the thread.
class read_ahead_reader final : public key_reader {
public:
    read_ahead_reader(std::unique_ptr<key_reader> inner, std::function<bool()> worth_it)
        : inner_(std::move(inner)), worth_it_(std::move(worth_it)) {}
    read_ahead_reader(const read_ahead_reader&) = delete;
    read_ahead_reader& operator=(const read_ahead_reader&) = delete;
    ~read_ahead_reader() override {
        if (!thread_.joinable()) return;
        {
            const std::lock_guard lock(mutex_);
            stopping_ = true;
            changed_.notify_all();
        }
        thread_.join();
    }

    bool next(std::string& track, raw_key& k) override {
        if (!thread_.joinable()) {
            if (inline_keys_ < inline_limit || !worth_it_) {
                ++inline_keys_;
                return inner_->next(track, k);
            }
            if (!std::exchange(worth_it_, nullptr)()) return inner_->next(track, k);
            thread_ = std::thread([this] { produce(); });
        }
        if (at_ == current_.keys.size()) {
            if (current_.last) {
                if (current_.failure) std::rethrow_exception(current_.failure);
                return false;
            }
            take();
            if (at_ == current_.keys.size()) return next(track, k);  // an empty last batch
        }
        auto& [name, key] = current_.keys[at_++];
        track.swap(name);  // the batch keeps the caller's string, to be written over
        k = std::move(key);
        return true;
    }
    // Both are settled before the first key comes out (a CSV header, the
    // first NDJSON line) and stay so: safe to ask while the thread reads.
    bool named() const override { return inner_->named(); }
    location start() const override { return inner_->start(); }

private:
    static constexpr std::size_t inline_limit = 1024, batch_keys = 1024, max_batches = 4;
    struct batch {
        std::vector<std::pair<std::string, raw_key>> keys;
        bool last = false;           // no keys after these
        std::exception_ptr failure;  // what ended the input early, with last
    };

    void produce() {
        batch b;
        while (!b.last) {
            b.keys.resize(batch_keys);
            std::size_t n = 0;
            try {
                while (n < batch_keys && inner_->next(b.keys[n].first, b.keys[n].second)) ++n;
                b.last = n < batch_keys;
            } catch (...) {
                b.last = true;
                b.failure = std::current_exception();
            }
            b.keys.resize(n);
            std::unique_lock lock(mutex_);
            changed_.wait(lock, [this] { return full_.size() < max_batches || stopping_; });
            if (stopping_) return;
            full_.push_back(std::move(b));
            changed_.notify_all();
            b = empty_.empty() ? batch{} : std::move(empty_.front());
            if (!empty_.empty()) empty_.pop_front();
        }
    }
    void take() {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [this] { return !full_.empty(); });
        empty_.push_back(std::move(current_));
        current_ = std::move(full_.front());
        full_.pop_front();
        at_ = 0;
        changed_.notify_all();
    }

    std::unique_ptr<key_reader> inner_;
    std::function<bool()> worth_it_;  // asked once, then empty
    std::size_t inline_keys_ = 0;
    batch current_;  // the caller's
    std::size_t at_ = 0;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<batch> full_, empty_;  // under mutex_
    bool stopping_ = false;           // under mutex_
    std::thread thread_;
};

}  // namespace

std::unique_ptr<key_reader> read_ahead(std::unique_ptr<key_reader> reader, std::function<bool()> worth_it) {
    return std::make_unique<read_ahead_reader>(std::move(reader), std::move(worth_it));
}

}  // namespace keyrot
