// SPDX-License-Identifier: MIT
// The row pipeline: batches formatted on other threads come out whole and
// in order, however their formatting threads or the output are held up.
#include "io/fast/row_pipeline.hpp"

#include <doctest/doctest.h>

#include <chrono>
#include <functional>
#include <sstream>
#include <string>
#include <thread>

using namespace keyrot;

namespace {

using milliseconds = std::chrono::milliseconds;
/// How long formatting a row of this frame number takes, beyond its text.
using row_delay = std::function<milliseconds(long long)>;

/// Writes each row's frame number on a line, each row held up as `delay`
/// says, as on a thread taken off its core: the other thread's later
/// batches are then formatted before their turn.
class frame_writer final : public table_writer {
public:
    frame_writer(std::string& out, row_delay delay) : out_(out), delay_(std::move(delay)) {}
    void begin_track(const std::string&, channels) override {}
    void row(const table_row& r) override {
        const auto frame = static_cast<long long>(r.frame.value_or(-1));
        std::this_thread::sleep_for(delay_(frame));
        out_ += std::to_string(frame) + '\n';
    }
    void finish() override {}
    std::unique_ptr<table_writer> row_writer(std::string& out) const override {
        return std::make_unique<frame_writer>(out, delay_);
    }

private:
    std::string& out_;
    row_delay delay_;
};

/// A stream whose every write takes a while, as a full pipe's.
class slow_buffer final : public std::stringbuf {
public:
    static constexpr milliseconds write_time{8};

protected:
    std::streamsize xsputn(const char* s, std::streamsize n) override {
        std::this_thread::sleep_for(write_time);
        return std::stringbuf::xsputn(s, n);
    }
};

/// 100,000 rows through a pipeline of two formatting threads into `buffer`:
/// they must come out whole and in order. Batches hold 4,096 rows after the
/// first 4,096 (formatted before the threads start).
void check_rows_in_order(std::stringbuf& buffer, const row_delay& delay) {
    std::ostream out(&buffer);
    std::string expected;
    {
        detail::chunked_output sink(std::nullopt, out, commit_mode{});
        frame_writer writer(sink.text(), delay);
        detail::row_pipeline rows(writer, sink, 2);
        rows.begin_track("t", channels{});
        for (int i = 0; i < 100000; ++i) {
            sample s;
            s.time = i / 24.0, s.frame = i;
            rows.frame(s);
            expected += std::to_string(i) + '\n';
        }
        rows.finish();
        sink.finish();
    }
    CHECK(buffer.str() == expected);
}

}  // namespace

TEST_CASE("row_pipeline: batches formatted before their turn are put out in turn") {
    // A slow row in the third batch, then one in the eighth, while the
    // other thread runs ahead.
    for (const long long slow : {4096LL * 3 + 7, 4096LL * 8}) {
        CAPTURE(slow);
        std::stringbuf buffer;
        check_rows_in_order(buffer, [slow](long long frame) { return milliseconds(frame == slow ? 30 : 0); });
    }
}

TEST_CASE("row_pipeline: a batch parked while a parked one is put out is not left behind") {
    // Each batch takes about as long to format as to write (from half as
    // long to half again as long, it still happens): a thread parks its batch,
    // formats the next, and parks that too while the other thread puts out
    // the first. Were that one left behind, both threads would wait for it
    // for ever (ctest's timeout).
    slow_buffer buffer;
    check_rows_in_order(buffer,
                        [](long long frame) { return frame % 4096 == 0 ? slow_buffer::write_time : milliseconds(0); });
}
