// SPDX-License-Identifier: MIT
// Keys parsed ahead on other threads: the same keys and errors, in order.
#include "io/fast/read_ahead.hpp"
#include "io/open.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <sstream>

#include "helpers.hpp"
#include "reading.hpp"
#include <thread>

#include "io/json/json.hpp"

using namespace keyrot;
using keyrot::test::read_all;
using keyrot::test::reading_result;

namespace {

/// A track of `n` keys, key i on line i + 2 (the track's name changes
/// halfway, to one too long to be stored in place), with a bad number on
/// line `bad_line`, if any. NDJSON's first line is a blank one.
std::string numbered_keys(std::size_t n, std::size_t bad_line = 0, format f = format::csv) {
    std::string text = f == format::csv ? "track,time,qw,qx,qy,qz\n" : "\n";
    for (std::size_t i = 0; i < n; ++i) {
        const std::string name = i < n / 2 ? "a" : "a track with a long name";
        const std::string qz = i + 2 == bad_line ? (f == format::csv ? "x" : "\"x\"") : std::to_string(i);
        text += f == format::csv ? fmt::format("{},{},1,0,0,{}\n", name, i, qz)
                                 : fmt::format("{{\"track\": \"{}\", \"time\": {}, \"quat\": [1, 0, 0, {}]}}\n", name, i, qz);
    }
    return text;
}

}  // namespace

TEST_CASE("read_ahead: the same keys and errors as the reader it wraps, in order") {
    // Both are parsed on two threads, a batch each in turn.
    for (const format f : {format::csv, format::ndjson}) {
        CAPTURE(f == format::csv);
        std::ostringstream err;
        warnings warn(err, "in");
        read_options o;
        o.source = "in";
        const auto read = [&](const std::string& text, bool ahead, int& asked, std::size_t at_most = SIZE_MAX) {
            std::istringstream in(text);
            const auto reader = ahead ? make_key_reader(in, f, o, warn, [&asked] { return ++asked > 0; })
                                      : make_key_reader(in, f, o, warn);
            return read_all(*reader, at_most);
        };
        const auto same = [](const reading_result& a, const reading_result& b) {
            REQUIRE(a.keys.size() == b.keys.size());
            for (std::size_t i = 0; i < a.keys.size(); ++i) {
                CAPTURE(i);
                CHECK(a.keys[i].first == b.keys[i].first);
                CHECK(a.keys[i].second.at.line == b.keys[i].second.at.line);
                CHECK(a.keys[i].second.time == b.keys[i].second.time);
                CHECK(a.keys[i].second.values == b.keys[i].second.values);
            }
            CHECK(a.error == b.error);
        };
        int asked = 0;
        // Keys and line numbers straight from the text: key i is on line i + 2.
        const reading_result plain = read(numbered_keys(5000, 0, f), false, asked);
        REQUIRE(plain.keys.size() == 5000);
        CHECK(plain.keys[4999].second.at.line == 5001);
        CHECK(plain.keys[4999].second.values[3] == 4999);
        CHECK(plain.keys[4999].first == "a track with a long name");
        CHECK(plain.error.empty());
        same(read(numbered_keys(5000, 0, f), true, asked), plain);
        CHECK(asked == 1);

        // The error after the keys before it, whether in the threads' first
        // batch, a later one, or among the keys read before they start.
        for (const std::size_t bad : std::initializer_list<std::size_t>{3000, 1025, 1026, 2050, 5001, 500}) {
            CAPTURE(bad);
            const reading_result expected = read(numbered_keys(5000, bad, f), false, asked);
            CHECK(expected.keys.size() == bad - 2);
            CHECK(expected.error == (f == format::csv
                                         ? fmt::format("in:{}: column 'qz': expected a finite number, got 'x'", bad)
                                         : fmt::format("in:{}: 'quat[3]': expected a number, got string \"x\"", bad)));
            same(read(numbered_keys(5000, bad, f), true, asked), expected);
        }

        // Batches of no keys (a run of blank lines) and keys after them.
        std::string gaps = numbered_keys(3000, 0, f);
        const auto key_1200 = gaps.find(f == format::csv ? "\na,1200," : "\n{\"track\": \"a\", \"time\": 1200,");
        REQUIRE(key_1200 != std::string::npos);
        gaps.insert(key_1200 + 1, std::string(5000, '\n'));
        const reading_result with_gaps = read(gaps, false, asked);
        REQUIRE(with_gaps.keys.size() == 3000);
        CHECK(with_gaps.keys[1199].second.at.line == 1201);
        CHECK(with_gaps.keys[1200].second.at.line == 6202);
        same(read(gaps, true, asked), with_gaps);

        // A small input never asks; a caller that stops early (the threads
        // a few batches ahead, waiting) ends without hanging.
        asked = 0;
        same(read(numbered_keys(1000, 0, f), true, asked), read(numbered_keys(1000, 0, f), false, asked));
        CHECK(asked == 0);
        const reading_result first = read(numbered_keys(20000, 0, f), true, asked, 1500);
        CHECK(first.keys.size() == 1500);
        CHECK(first.keys[1499].second.values[3] == 1499);
        CHECK(asked == 1);

        // Not worth it: all on the caller's thread, the same again.
        std::istringstream in(numbered_keys(3000, 2500, f));
        const auto no_thread = make_key_reader(in, f, o, warn, [&asked] { return ++asked < 0; });
        same(read_all(*no_thread), read(numbered_keys(3000, 2500, f), false, asked));
        CHECK(asked == 2);
    }

    // NDJSON's lines name their tracks all or none, as the first key says:
    // a line that breaks the rule is found, and worded, as on the caller's
    // thread, also first in a thread's first batch (lines 1025 and 2049,
    // the keys before them read on the caller's thread).
    for (const std::size_t change : std::initializer_list<std::size_t>{1025, 2049, 3000}) {
        for (const bool named_first : {true, false}) {
            CAPTURE(change);
            CAPTURE(named_first);
            std::string text;
            for (std::size_t i = 0; i < 5000; ++i) {  // key i on line i + 1
                const bool named = (i + 1 < change) == named_first;
                text += fmt::format("{{{}\"time\": {}, \"quat\": [1, 0, 0, {}]}}\n", named ? "\"track\": \"a\", " : "", i, i);
            }
            std::ostringstream err;
            warnings warn(err, "in");
            read_options o;
            o.source = "in";
            const auto read = [&](bool ahead) {
                std::istringstream in(text);
                const auto reader = ahead ? make_key_reader(in, format::ndjson, o, warn, [] { return true; })
                                          : make_key_reader(in, format::ndjson, o, warn);
                return read_all(*reader);
            };
            const reading_result alone = read(false), ahead = read(true);
            CHECK(alone.keys.size() == change - 1);
            CHECK(alone.error ==
                  fmt::format("in:{}: some lines have a 'track' and some do not: expected all or none", change));
            CHECK(ahead.keys.size() == alone.keys.size());
            CHECK(ahead.error == alone.error);
        }
    }

    // numpy's commented header: its first key is read with the header, and
    // comes out first.
    std::string numpy = "# time,qw,qx,qy,qz\n";
    for (int i = 0; i < 3000; ++i) numpy += fmt::format("{}.0e+00,1,0,0,{}\n", i, i);
    std::ostringstream err;
    warnings warn(err, "in");
    read_options o;
    o.source = "in";
    std::istringstream in(numpy);
    const auto ahead = make_key_reader(in, format::csv, o, warn, [] { return true; });
    const reading_result all = read_all(*ahead);
    REQUIRE(all.keys.size() == 3000);
    for (std::size_t i = 0; i < all.keys.size(); ++i) {
        CAPTURE(i);
        CHECK(all.keys[i].second.at.line == i + 2);
        CHECK(all.keys[i].second.values[3] == static_cast<double>(i));
    }
}

TEST_CASE("read_ahead: a reader without a line parser is read on the caller's thread") {
    // NDJSON has a parser only once its first key has said whether lines
    // name their tracks; read_ahead starts no threads without one.
    std::ostringstream err;
    warnings warn(err, "in");
    read_options o;
    std::istringstream in("\n{\"time\": 0, \"quat\": [1, 0, 0, 0]}\n");
    const auto ndjson = make_ndjson_reader(in, o, warn);
    CHECK(ndjson->parser() == nullptr);
    std::string name;
    raw_key k;
    REQUIRE(ndjson->next(name, k));
    CHECK(ndjson->parser() != nullptr);
    CHECK_FALSE(ndjson->named());

    struct counting_reader final : line_key_reader {
        std::size_t count = 0;
        bool elsewhere = false;  // next() called on another thread
        std::thread::id caller = std::this_thread::get_id();
        bool next(std::string&, raw_key& key) override {
            elsewhere = elsewhere || std::this_thread::get_id() != caller;
            key.time = static_cast<double>(count);
            return count++ < 5000;
        }
        bool named() const override { return false; }
        location start() const override { return {}; }
        const key_settings& settings() const override { return defaults; }
        std::unique_ptr<line_parser> parser() const override { return nullptr; }
        bool next_line(std::string_view&, text_place&) override { return false; }
        key_settings defaults;
    };
    auto inner = std::make_unique<counting_reader>();
    const counting_reader& counted = *inner;
    int asked = 0;
    const auto reader = read_ahead(std::move(inner), [&asked] { return ++asked > 0; });
    const reading_result all = read_all(*reader);
    REQUIRE(all.keys.size() == 5000);
    CHECK(all.keys[4999].second.time == 4999);
    CHECK(asked == 1);
    CHECK_FALSE(counted.elsewhere);
}

