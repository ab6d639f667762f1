// SPDX-License-Identifier: MIT
#pragma once
// How output rows get formatted, on other threads once there are many, and
// written out: what open_table (io/open.hpp) puts a table through.
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "ground/thread_start.hpp"
#include "io/common/chunked_output.hpp"
#include "io/common/table_writer.hpp"
#include "keyrot/error.hpp"
#include "keyrot/interpolate.hpp"
#include "keyrot/resample.hpp"

namespace keyrot::detail {

/// Rows are formatted on other threads once the output is large (for small
/// ones starting threads costs more than it saves): the caller, reading and
/// resampling, hands over batches of rows in order; a bounded queue keeps
/// memory constant. Where rows stand alone (CSV, NDJSON) each thread formats
/// whole batches with its own row_writer and writes their texts out itself,
/// in batch order (a writing thread besides would be one more thread to
/// share the cores); JSON rows go through the one writer, on one thread.
/// Errors of the formatting threads come back from the next call, or from
/// finish().
/// Slerp and squad frames may come as their segment's keys and their
/// times: the formatting threads then work out their rotations, which
/// would keep the reading thread, the one they wait for, busier.
class row_pipeline final : public arc_frame_sink {
public:
    row_pipeline(table_writer& writer, chunked_output& out, unsigned threads)
        : writer_(writer), out_(out), threads_(threads) {}
    row_pipeline(const row_pipeline&) = delete;
    row_pipeline& operator=(const row_pipeline&) = delete;
    ~row_pipeline() {
        stop();
        for (auto& w : workers_) w->thread.join();
    }
    void begin_track(const std::string& name, channels carried) {
        current_ = track_begin{batch_.rows.size(), name, carried};
        if (workers_.empty()) return writer_.begin_track(name, carried);
        batch_.begins.push_back(*current_);
    }
    void row(const table_row& s) {
        if (workers_.empty()) return inline_row(s);
        if (alone(s) && !s.own) return pack(s);
        add_full(s);
    }
    /// A row that is a sample as it is (resample's frames).
    void frame(const sample& s) {
        if (workers_.empty()) return inline_row(table_row{s});
        if (alone(s)) return pack(s);
        add_full(table_row{s});
    }
    void keys(const arc_keys& k) override {
        arc_ = k;
        arc_index_ = packed_row::none;
        inline_curve_.reset();
    }
    void frame(double frame, double time) override {
        if (workers_.empty()) {
            if (!inline_curve_) inline_curve_.emplace(arc_);
            sample s;
            s.time = time, s.frame = frame, s.rotation = inline_curve_->at(segment_fraction(arc_.t0, arc_.t1, time));
            return inline_row(table_row{s});
        }
        if (arc_index_ == packed_row::none) {  // the keys' first frame in this batch
            arc_index_ = static_cast<std::uint32_t>(batch_.arcs.size());
            batch_.arcs.push_back(arc_);
        }
        batch_.rows.push_back({time, frame, {}, packed_row::arc | arc_index_, true});
        if (batch_.rows.size() == batch_rows) hand_over();
    }
    void finish() {
        if (workers_.empty()) return;
        hand_over();
        stop();
        for (auto& w : workers_) w->thread.join();
        workers_.clear();
        if (failure_) std::rethrow_exception(failure_);
    }

private:
    static constexpr std::size_t inline_limit = 4096, batch_rows = 4096, max_batches = 6;
    struct track_begin {
        std::size_t before_row;
        std::string name;
        channels carried;
    };
    /// A row as it waits in a batch: its rotation, time and frame, or where it is in full.
    struct packed_row {
        static constexpr std::uint32_t none = UINT32_MAX, arc = 1u << 31;
        double time, frame;
        quat rotation;
        // none; its index in batch::full (fewer than batch_rows); or a slerp
        // or squad frame, its rotation to be worked out: arc | its keys' index in batch::arcs
        std::uint32_t full;
        bool has_frame;

        table_row unpacked() const {
            table_row r;
            r.time = time, r.rotation = rotation;
            if (has_frame) r.frame = frame;
            return r;
        }
    };
    struct batch {
        std::size_t number = 0;
        std::optional<track_begin> resumed;  // the track the rows before the first begin belong to
        std::vector<packed_row> rows;
        std::vector<table_row> full;  // the rows with more than a rotation
        std::vector<double> weights;  // their morph weights, one after another
        std::vector<frame_rates> rates;  // their angular velocities and accelerations, likewise
        std::vector<own_rotation> owns;  // their own rotation values, likewise
        std::vector<track_begin> begins;
        std::vector<arc_keys> arcs;  // the slerp and squad frames' segments

        /// Empty, its memory kept: already mapped, unlike a new vector's.
        void clear() {
            resumed.reset();
            rows.clear(), full.clear(), weights.clear(), rates.clear(), owns.clear(), begins.clear(), arcs.clear();
        }
    };
    struct parked_text {
        std::size_t number;
        std::string text;
    };
    struct worker {
        std::unique_ptr<table_writer> own;  // formats into text; none: the one writer, straight out
        std::string text;
        std::thread thread;
    };

    void inline_row(const table_row& s) {
        writer_.row(s);
        out_.maybe_flush();
        if (++inline_rows_ == inline_limit) start();
    }
    /// A rotation with its time and frame alone, as nearly every row is.
    static bool alone(const sample& s) { return !s.translation && !s.scale && s.weights.empty() && !s.rates; }
    /// Such a row goes over in a third of the bytes: this thread is the one the others wait for.
    void pack(const sample& s) {
        batch_.rows.push_back({s.time, s.frame.value_or(0), s.rotation, packed_row::none, s.frame.has_value()});
        if (batch_.rows.size() == batch_rows) hand_over();
    }
    void add_full(const table_row& s) {
        batch_.rows.push_back({0, 0, {}, static_cast<std::uint32_t>(batch_.full.size()), false});
        batch_.full.push_back(s);
        batch_.full.back().spline = nullptr;  // (a table has no place for it, and it lives as long as this call)
        // The weights the row views live as long as this call: the batch keeps them (format() views them there).
        if (!s.weights.empty()) batch_.weights.insert(batch_.weights.end(), s.weights.begin(), s.weights.end());
        if (s.rates) batch_.rates.push_back(*s.rates);  // (likewise)
        if (s.own) batch_.owns.push_back(*s.own);
        if (batch_.rows.size() == batch_rows) hand_over();
    }
    /// Starts the workers the system gives threads to: with none, every row
    /// is formatted on this thread, as for a small output.
    void start() {
        std::vector<std::unique_ptr<worker>> workers;
        for (unsigned i = 0; i < threads_; ++i) {
            auto w = std::make_unique<worker>();
            if (threads_ > 1) w->own = writer_.row_writer(w->text);
            if (i > 0 && !w->own) break;
            workers.push_back(std::move(w));
        }
        batch_.rows.reserve(batch_rows);
        if (current_) batch_.resumed = track_begin{0, current_->name, current_->carried};
        // The texts the batches are formatted into (each thread's, and the
        // spare ones parking goes round with) are made large enough for a
        // batch once (as large as the rows formatted here so far, and a
        // quarter more for longer numbers later), not grown in steps, each
        // a copy into pages never touched.
        if (!workers.empty() && workers.front()->own) {
            text_room_ = out_.text().size() * batch_rows / inline_limit * 5 / 4;
            for (auto& w : workers) w->text.reserve(text_room_);
        }
        workers_.reserve(workers.size());
        for (auto& w : workers) {
            if (!try_start_thread(w->thread, [this, &w = *w] { consume(w); })) break;
            workers_.push_back(std::move(w));
        }
    }
    void hand_over() {
        {
            std::unique_lock lock(mutex_);
            room_.wait(lock, [this] { return queue_.size() < max_batches || failure_; });
            if (failure_) std::rethrow_exception(failure_);
            queue_.push_back(std::move(batch_));
            if (spare_.empty()) {
                batch_ = batch{};
                batch_.rows.reserve(batch_rows);
            } else {
                batch_ = std::move(spare_.back());
                spare_.pop_back();
            }
        }
        work_.notify_one();
        batch_.number = ++batches_;
        arc_index_ = packed_row::none;
        if (current_) batch_.resumed = track_begin{0, current_->name, current_->carried};
    }
    void stop() {
        {
            const std::lock_guard lock(mutex_);
            done_ = true;
        }
        work_.notify_all();
    }
    void consume(worker& w) {
        try {
            for (batch b; take(b);) {
                format(b, w);
                if (w.own && !put_in_turn(b.number, w.text)) return;
            }
        } catch (...) {
            {
                const std::lock_guard lock(mutex_);
                if (!failure_) failure_ = std::current_exception();
            }
            for (auto* waiting : {&work_, &room_, &turn_}) waiting->notify_all();
        }
    }
    /// Puts out batch `number`'s text in its turn, then any parked text
    /// that follows. Formatted before its turn, the text is parked (unless
    /// another is) and `text` left another buffer: the thread goes on to the
    /// next batch rather than waiting for one that may be off its core (as
    /// one of three busy threads on two cores often is, with squad or matrix
    /// output). False after another thread failed.
    bool put_in_turn(std::size_t number, std::string& text) {
        std::unique_lock lock(mutex_);
        if (written_ != number && !parked_) {
            parked_ = parked_text{number, std::move(text)};
            text = spare_text();
            return true;
        }
        turn_.wait(lock, [&] { return written_ == number || failure_; });
        if (failure_) return false;
        lock.unlock();
        out_.write_here(text);  // this batch's turn: no other thread writes now
        lock.lock();
        // (while one is put out, the next may be parked: the loop)
        for (++written_; parked_ && parked_->number == written_; ++written_) {
            std::string parked = std::move(parked_->text);
            parked_.reset();
            lock.unlock();
            out_.write_here(parked);  // (which leaves it an empty buffer)
            lock.lock();
            spare_texts_.push_back(std::move(parked));
        }
        lock.unlock();
        turn_.notify_all();
        return true;
    }
    /// An empty text with room for a batch, for a thread that parks its own:
    /// one that a parked text was put out from, else a new one. Under mutex_.
    std::string spare_text() {
        std::string text;
        if (spare_texts_.empty()) {
            text.reserve(text_room_);
        } else {
            text = std::move(spare_texts_.back());
            spare_texts_.pop_back();
        }
        return text;
    }
    bool take(batch& b) {
        {
            std::unique_lock lock(mutex_);
            work_.wait(lock, [this] { return !queue_.empty() || done_ || failure_; });
            if (queue_.empty() || failure_) return false;
            if (b.rows.capacity() != 0) {  // formatted: its memory for the next batches
                b.clear();
                spare_.push_back(std::move(b));
            }
            b = std::move(queue_.front());
            queue_.pop_front();
        }
        room_.notify_one();
        return true;
    }
    void format(const batch& b, worker& w) {
        table_writer& writer = w.own ? *w.own : writer_;
        if (w.own && b.resumed) writer.begin_track(b.resumed->name, b.resumed->carried);
        std::size_t next_begin = 0, weights = 0, rates = 0, owns = 0;
        const bool weighted = !b.weights.empty() || !b.rates.empty() || !b.owns.empty();
        std::optional<arc_curve> curve;  // of b.arcs[curve_of]
        std::uint32_t curve_of = packed_row::none;
        for (std::size_t i = 0; i <= b.rows.size(); ++i) {
            for (; next_begin < b.begins.size() && b.begins[next_begin].before_row == i; ++next_begin)
                writer.begin_track(b.begins[next_begin].name, b.begins[next_begin].carried);
            if (i == b.rows.size()) break;
            const packed_row& p = b.rows[i];
            if (p.full == packed_row::none) {
                writer.row(p.unpacked());
            } else if (p.full & packed_row::arc) {
                const std::uint32_t keys = p.full & ~packed_row::arc;
                if (keys != curve_of) curve.emplace(b.arcs[keys]), curve_of = keys;
                table_row r = p.unpacked();
                r.rotation = curve->at(segment_fraction(b.arcs[keys].t0, b.arcs[keys].t1, p.time));
                writer.row(r);
            } else if (!weighted || (b.full[p.full].weights.empty() && !b.full[p.full].rates && !b.full[p.full].own)) {
                writer.row(b.full[p.full]);
            } else {
                table_row s = b.full[p.full];
                s.weights = std::span(b.weights).subspan(weights, s.weights.size());
                weights += s.weights.size();
                if (s.rates) s.rates = &b.rates[rates++];
                if (s.own) s.own = &b.owns[owns++];
                writer.row(s);
            }
            if (!w.own) out_.maybe_flush();
        }
    }

    table_writer& writer_;
    chunked_output& out_;
    unsigned threads_;
    std::size_t inline_rows_ = 0;
    batch batch_;
    std::optional<track_begin> current_;
    arc_keys arc_;                                // the slerp or squad frames' segment
    std::uint32_t arc_index_ = packed_row::none;  // its index in batch_.arcs, once there
    std::optional<arc_curve> inline_curve_;       // its curve, for frames formatted here
    std::size_t batches_ = 0, written_ = 0;
    std::deque<batch> queue_;
    std::optional<parked_text> parked_;  // formatted before its turn
    // Empty, for the threads that park to go on with: a text parked while a
    // parked one is put out takes another, and each is kept, never freed
    // and made again on pages never touched.
    std::vector<std::string> spare_texts_;
    std::size_t text_room_ = 0;  // what each text is made room for
    std::vector<batch> spare_;  // formatted, for the next batches, so that no row lands on a fresh page
    // One lock; a condition each for what a thread waits for (a batch, room
    // for one, its turn to put out), so that a change wakes only the threads
    // it concerns, and after the lock is let go.
    std::mutex mutex_;
    std::condition_variable work_, room_, turn_;
    bool done_ = false;
    std::exception_ptr failure_;
    std::vector<std::unique_ptr<worker>> workers_;  // their threads start once everything else exists
};

/// Threads for formatting a large output: two keep up with one reading
/// and resampling thread; more than four do not help.
inline unsigned formatting_threads() { return std::clamp(std::thread::hardware_concurrency(), 2u, 4u); }

}  // namespace keyrot::detail
