// The row pipeline: batches formatted on other threads come out whole and
// in order, however their formatting threads are held up.
#include "io/fast/row_pipeline.hpp"

#include <doctest/doctest.h>

#include <chrono>
#include <sstream>
#include <string>
#include <thread>

using namespace keyrot;

namespace {

/// Writes each row's frame number on a line. Rows of `slow` frames take a
/// while, as on a thread taken off its core: the other thread's later
/// batches are then formatted before their turn.
class frame_writer final : public table_writer {
public:
    frame_writer(std::string& out, double slow) : out_(out), slow_(slow) {}
    void begin_track(const std::string&, channels) override {}
    void row(const table_row& r) override {
        if (r.frame && *r.frame == slow_) std::this_thread::sleep_for(std::chrono::milliseconds(30));
        out_ += std::to_string(static_cast<long long>(r.frame.value_or(-1))) + '\n';
    }
    void finish() override {}
    std::unique_ptr<table_writer> row_writer(std::string& out) const override {
        return std::make_unique<frame_writer>(out, slow_);
    }

private:
    std::string& out_;
    double slow_;
};

}  // namespace

TEST_CASE("row_pipeline: batches formatted before their turn are put out in turn") {
    // Batches of 4,096 rows after the first 4,096: a slow row in the third
    // batch, then one in the eighth, while the other thread runs ahead.
    for (const double slow : {4096.0 * 3 + 7, 4096.0 * 8}) {
        CAPTURE(slow);
        std::ostringstream out;
        std::string expected;
        {
            detail::chunked_output sink(std::nullopt, out, commit_mode{});
            frame_writer writer(sink.text(), slow);
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
        CHECK(out.str() == expected);
    }
}
