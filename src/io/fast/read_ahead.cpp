// SPDX-License-Identifier: MIT
#include <array>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include "ground/thread_start.hpp"
#include "io/fast/read_ahead.hpp"

namespace keyrot {
namespace {

/// Parses keys on threads of their own, batches ahead of the caller, so that
/// reading a long input overlaps with what the caller does with its keys.
/// Two threads take turns, each with a copy of the inner reader's line
/// parser: each copies the next batch's lines under a lock, in order, then
/// parses them while the other copies. The first keys are read on the
/// caller's thread: a small input never starts the threads, nor one where
/// worth_it() then says no, or whose reader has no parser. What the inner
/// reader throws comes out of next() after the keys before it, as it would
/// without the threads.
class read_ahead_reader final : public key_reader {
public:
    read_ahead_reader(std::unique_ptr<line_key_reader> inner, std::function<bool()> worth_it)
        : inner_(std::move(inner)), worth_it_(std::move(worth_it)) {}
    read_ahead_reader(const read_ahead_reader&) = delete;
    read_ahead_reader& operator=(const read_ahead_reader&) = delete;
    ~read_ahead_reader() override {
        {
            const std::lock_guard lock(mutex_);
            stopping_ = true;
            changed_.notify_all();
        }
        for (auto& t : threads_) t.join();
    }

    bool next(std::string& track, raw_key& k) override {
        if (threads_.empty()) {
            if (inline_keys_ < inline_limit || !worth_it_) {
                ++inline_keys_;
                return inner_->next(track, k);
            }
            if (!std::exchange(worth_it_, nullptr)() || !start()) return inner_->next(track, k);
        }
        while (at_ == current_.keys.size()) {  // (a batch may have no keys: blank lines, comments)
            if (current_.last) {
                if (current_.failure) std::rethrow_exception(current_.failure);
                return false;
            }
            take();
        }
        settings_ = current_.settings[at_];
        auto& [name, key] = current_.keys[at_++];
        track.swap(name);  // the batch keeps the caller's string, to be written over
        k = std::move(key);
        return true;
    }
    // Both are settled before the first key comes out (a CSV header, the
    // first NDJSON line) and stay so: safe to ask while the threads read.
    bool named() const override { return inner_->named(); }
    location start() const override { return inner_->start(); }
    /// The parser's for the key given last, or the inner reader's.
    const key_settings& settings() const override { return settings_ ? *settings_ : inner_->settings(); }
    /// Asked once next() returned false: the threads have stopped reading.
    bool declined() const override { return inner_->declined(); }

private:
    static constexpr std::size_t inline_limit = 1024, batch_lines = 1024, max_batches = 4;
    struct batch {
        std::vector<std::pair<std::string, raw_key>> keys;
        std::vector<const key_settings*> settings;               // each key's, where the parser has them
        std::string text;                                        // the lines
        std::vector<std::pair<std::size_t, text_place>> lines;  // each one's end in text, and its place
        bool last = false;                                       // no keys after these
        std::exception_ptr failure;                              // what ended the input early, with last
    };

    /// False, and no threads, for a reader without a parser or where the
    /// system refuses threads (one thread reads alone: it takes every turn).
    bool start() {
        auto first = inner_->parser();
        if (!first) return false;
        parsers_.push_back(std::move(first));
        parsers_.push_back(inner_->parser());
        threads_.reserve(parsers_.size());
        for (auto& p : parsers_) {
            std::thread t;
            if (!try_start_thread(t, [this, parser = p.get()] { work(*parser); })) break;
            threads_.push_back(std::move(t));
        }
        return !threads_.empty();
    }

    /// Batch after batch: its lines copied in turn, then parsed apart.
    void work(line_parser& parser) {
        for (;;) {
            batch b;
            std::size_t number = 0;
            {
                const std::lock_guard turn(reading_);
                {
                    std::unique_lock lock(mutex_);
                    changed_.wait(lock, [this] { return stopping_ || ended_ || numbered_ < taken_ + max_batches; });
                    if (stopping_ || ended_) return;
                    number = numbered_++;
                    if (!spare_.empty()) b = std::move(spare_.back()), spare_.pop_back();
                }
                b.last = false;
                b.failure = nullptr;
                copy_lines(b);
            }
            parse(b, parser);
            const std::lock_guard lock(mutex_);
            if (b.last) ended_ = true;  // the end, or an error: no batches after this one
            ready_[number % max_batches] = std::move(b);
            changed_.notify_all();
        }
    }
    /// In a catch block: what was thrown ends the input after b's keys.
    static void failed(batch& b) {
        b.last = true;
        b.failure = std::current_exception();
    }
    void copy_lines(batch& b) {
        b.text.clear();
        b.lines.clear();
        try {
            std::string_view line;
            text_place at;
            while (b.lines.size() < batch_lines && inner_->next_line(line, at)) {
                b.text += line;
                b.lines.emplace_back(b.text.size(), at);
            }
            b.last = b.lines.size() < batch_lines;
        } catch (...) {
            failed(b);
        }
    }
    static void parse(batch& b, line_parser& parser) {
        std::size_t n = 0, begin = 0;
        try {
            b.keys.resize(b.lines.size());
            b.settings.resize(b.lines.size());
            for (const auto& [end, at] : b.lines) {
                const std::string_view line(b.text.data() + begin, end - begin);
                begin = end;
                if (parser.parse(line, at, b.keys[n].first, b.keys[n].second)) b.settings[n++] = parser.settings();
            }
        } catch (...) {  // the keys before it still go out
            failed(b);
        }
        b.keys.resize(n);
        b.settings.resize(n);
    }
    void take() {
        std::unique_lock lock(mutex_);
        std::optional<batch>& next = ready_[taken_ % max_batches];
        changed_.wait(lock, [&] { return next.has_value(); });
        spare_.push_back(std::move(current_));
        current_ = std::move(*next);
        next.reset();
        ++taken_;
        at_ = 0;
        changed_.notify_all();
    }

    std::unique_ptr<line_key_reader> inner_;
    std::function<bool()> worth_it_;  // asked once, then empty
    std::size_t inline_keys_ = 0;
    batch current_;  // the caller's
    std::size_t at_ = 0;
    const key_settings* settings_ = nullptr;  // the parser's, for the key given last
    std::vector<std::unique_ptr<line_parser>> parsers_;  // one to a thread
    std::mutex reading_;                                 // inner_'s turn: batches are numbered and read in order
    std::mutex mutex_;
    std::condition_variable changed_;
    // Under mutex_: batch n, once parsed, at n % max_batches until the caller
    // takes it (batches begin fewer than max_batches ahead of the caller).
    // Handing a batch on allocates nothing: it cannot fail where no one
    // would hear of it.
    std::array<std::optional<batch>, max_batches> ready_;
    std::vector<batch> spare_;                // under mutex_: taken batches, their memory for new ones
    std::size_t numbered_ = 0, taken_ = 0;    // under mutex_: batches begun, batches the caller took
    bool ended_ = false, stopping_ = false;   // under mutex_
    std::vector<std::thread> threads_;
};

}  // namespace

std::unique_ptr<key_reader> read_ahead(std::unique_ptr<line_key_reader> reader, std::function<bool()> worth_it) {
    return std::make_unique<read_ahead_reader>(std::move(reader), std::move(worth_it));
}

}  // namespace keyrot
