// SPDX-License-Identifier: MIT
// The BVH reader gives a take's keys joint after joint, and stops at the
// first error; bvh_output takes them back track after track and writes a
// line per frame; track_store holds the rows between.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <map>
#include <sstream>
#include <string>

#include "io/bvh/bvh_read.hpp"
#include "io/bvh/bvh_write.hpp"
#include "io/bvh/track_store.hpp"
#include "reading.hpp"

namespace keyrot::test {
namespace {

const std::string take =
    "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation "
    "Yrotation\n  JOINT Leg\n  {\n    OFFSET 0 -1 0\n    CHANNELS 3 Yrotation Xrotation Zrotation\n"
    "    End Site\n    {\n      OFFSET 0 -1 0\n    }\n  }\n}\nMOTION\nFrames: 3\nFrame Time: 0.04\n"
    "0 0 0 0 0 0 0 0 0\n1 2 3 10 20 30 40 50 60\n\n4 5 6 -10 -20 -30 -40 -50 -60\n";

/// The reading options of "take.bvh".
read_options take_options() {
    read_options o;
    o.source = "take.bvh";
    return o;
}

/// The hierarchy of `take`.
std::shared_ptr<bvh_source> take_source() {
    std::istringstream in(take);
    return read_bvh_source(in, take_options());
}

/// Each track's keys as the reader gives them, and the error it stopped at.
std::pair<std::map<std::string, std::vector<raw_key>>, std::string> by_track(const std::string& text,
                                                                             std::vector<std::string>* order = nullptr) {
    std::istringstream in(text);
    const auto reader = make_bvh_reader(in, take_options());
    const reading_result r = read_all(*reader);
    std::map<std::string, std::vector<raw_key>> tracks;
    for (const auto& [name, k] : r.keys) {
        tracks[name].push_back(k);
        if (order) order->push_back(name);
    }
    return {tracks, r.error};
}

}  // namespace

TEST_CASE("BVH: a take's keys joint after joint, each frame's values in its joint's channel order") {
    std::vector<std::string> order;
    const auto [tracks, error] = by_track(take, &order);
    CHECK(error.empty());
    CHECK(order == std::vector<std::string>{"Hips", "Hips", "Hips", "Leg", "Leg", "Leg"});
    REQUIRE(tracks.size() == 2);
    const raw_key& leg = tracks.at("Leg")[2];
    CHECK(leg.at.line == 22);     // after the blank line
    CHECK(leg.frame == 2);
    CHECK(leg.kind == rep::euler);
    CHECK(leg.values[0] == -40);  // Yrotation first: the sequence YXZ
    CHECK(leg.values[2] == -60);
    CHECK(!leg.translation);      // no position channels
    const raw_key& hips = tracks.at("Hips")[1];
    CHECK(hips.translation->y == 2);
    CHECK(hips.values[0] == 10);  // Zrotation first: ZXY
}

TEST_CASE("BVH: joints of one name are tracks '<name>', '<name>.2', '<name>.3'") {
    // Hips, and three joints named Leg, the third below the second and below
    // a joint named "Leg.2" (a name the second Leg took first).
    std::string text = take;
    const std::string leg = "  JOINT Leg\n  {\n    OFFSET 0 -1 0\n    CHANNELS 3 Yrotation Xrotation Zrotation\n";
    text.replace(text.find(leg), leg.size(), leg + leg + "  JOINT Leg.2\n  {\n    OFFSET 0 -1 0\n    CHANNELS 1 Zrotation\n" + leg);
    const std::string end = "    End Site\n    {\n      OFFSET 0 -1 0\n    }\n  }\n";
    text.replace(text.find(end), end.size(), end + "  }\n  }\n  }\n");
    const std::string frames = "0 0 0 0 0 0 0 0 0\n1 2 3 10 20 30 40 50 60\n\n4 5 6 -10 -20 -30 -40 -50 -60\n";
    text.replace(text.find(frames), frames.size(), "0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0\n1 2 3 10 20 30 40 50 60 1 2 3 7 4 5 6\n\n"
                                                  "4 5 6 -10 -20 -30 -40 -50 -60 1 2 3 7 4 5 6\n");
    std::vector<std::string> order;
    const auto [tracks, error] = by_track(text, &order);
    CHECK(error.empty());
    std::vector<std::string> names;  // in order of first appearance
    for (const std::string& name : order)
        if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    CHECK(names == std::vector<std::string>{"Hips", "Leg", "Leg.2", "Leg.2.2", "Leg.3"});
    CHECK(tracks.size() == 5);
}

TEST_CASE("BVH: a take that does not hold the frames its header states is an error naming the line") {
    for (const auto& bad : std::vector<std::pair<std::string, std::string>>{
             {take.substr(0, take.size() - 4) + "\n",
              "take.bvh:22: expected 9 values (the hierarchy's channels), got 8"},
             {take + "1 1 1 1 1 1 1 1 1\n", "take.bvh:23: a frame line after the 3 that 'Frames:' states"},
             {take.substr(0, take.rfind("4 5 6")), "'Frames: 3', but 2 frame lines"}}) {
        const std::string& text = bad.first;
        const std::string& message = bad.second;  // (not a structured binding: clang's lambdas in the checks)
        CAPTURE(message);
        CHECK(by_track(text).second.find(message) != std::string::npos);
    }
}

/// The descriptors this process has open.
std::size_t open_descriptors() {
    return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator("/proc/self/fd"), {}));
}

TEST_CASE("BVH: a take within one block makes no temporary file; a longer one comes back across the file's blocks") {
    // One channel: blocks of 4,096 frames.
    for (const std::size_t frames : {std::size_t{3}, std::size_t{10000}}) {
        std::string text = "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 1 Zrotation\n}\nMOTION\nFrames: " +
                           std::to_string(frames) + "\nFrame Time: 0.04\n";
        for (std::size_t f = 0; f < frames; ++f) text += std::to_string(f % 360) + "\n";
        CAPTURE(frames);
        const std::size_t before = open_descriptors();
        std::istringstream in(text);
        const auto reader = make_bvh_reader(in, take_options());
        const reading_result r = read_all(*reader);
        CHECK(r.error.empty());
        CHECK(open_descriptors() == before + (frames > 4096 ? 1 : 0));  // the temporary file, held while reading
        REQUIRE(r.keys.size() == frames);
        bool in_order = true;
        for (std::size_t f = 0; f < frames; ++f)
            in_order = in_order && r.keys[f].second.frame == static_cast<double>(f) &&
                       r.keys[f].second.values[0] == static_cast<double>(f % 360);
        CHECK(in_order);
    }
}

/// A BVH output row: time, the joint's angles in its sequence (degrees), position.
struct bvh_row {
    own_rotation angles;
    table_row row;
    bvh_row(double time, std::array<double, 3> degrees, vec3 position) : angles{{degrees[0], degrees[1], degrees[2], 0}} {
        row.time = time;
        row.translation = position;
    }
    /// The row, its angles held by this.
    operator const table_row&() {
        row.own = &angles;
        return row;
    }
};

TEST_CASE("bvh_output: tracks one after another, written as a line per frame in each joint's channel order") {
    std::ostringstream out;
    bvh_output file(std::nullopt, out, take_source(), 2, {});
    file.begin_track("Hips", {true, false, 0}, {});
    file.row(bvh_row(0, {90, 0, 0}, {1, 2, 3}));
    file.row(bvh_row(0.5, {0, 0, 0}, {4, 5, 6}));
    file.begin_track("Leg", {}, {});
    file.row(bvh_row(0, {0, 0, 90}, {}));
    file.row(bvh_row(0.5, {0, -0.5, 450}, {}));
    CHECK(out.str().empty());  // nothing before the last joint's rows
    file.finish();
    const std::string text = out.str();
    REQUIRE(text.rfind("MOTION\nFrames: 2\nFrame Time: 0.5\n") != std::string::npos);
    const std::string motion = text.substr(text.rfind("Frame Time: 0.5\n") + 16);
    // Hips: ZXY, positions first; Leg: YXZ, so z is its third channel; the angles as they come.
    CHECK(motion == "1 2 3 90 0 0 0 0 90\n4 5 6 0 0 0 0 -0.5 450\n");
    CHECK(text.substr(0, text.find("MOTION")) == take.substr(0, take.find("MOTION")));
    // A row without its angles is a caller's bug, said as one
    bvh_output other(std::nullopt, out, take_source(), std::nullopt, {});
    other.begin_track("Hips", {}, {});
    CHECK_THROWS_AS(other.row(table_row{}), std::logic_error);
}

TEST_CASE("bvh_output: at the input's own rate, its Frame Time as it was written") {
    std::ostringstream out;
    const auto source = take_source();
    bvh_output file(std::nullopt, out, source, source->fps, {});
    for (const char* joint : {"Hips", "Leg"}) {
        file.begin_track(joint, {}, {});
        file.row(bvh_row(0, {0, 0, 0}, {}));
    }
    file.finish();
    CHECK(out.str().find("Frame Time: " + source->frame_time_text + "\n") != std::string::npos);
}

TEST_CASE("bvh_output: tracks that do not make the same frames for every joint are an error") {
    const auto written = [](const std::vector<std::vector<bvh_row>>& tracks) {
        std::ostringstream out;
        bvh_output file(std::nullopt, out, take_source(), 2, {});
        for (const auto& rows : tracks) {
            file.begin_track("", {}, {});
            for (bvh_row r : rows) file.row(r);
        }
        file.finish();
        return out.str();
    };
    const bvh_row at0(0, {}, {}), at1(1, {}, {});
    CHECK(written({{at0, at1}, {at0, at1}}).find("Frames: 2") != std::string::npos);
    CHECK_THROWS_WITH_AS(written({{at0, at1}, {at0}}), doctest::Contains("'Leg' has 1 frames where 'Hips' has 2"), error);
    CHECK_THROWS_WITH_AS(written({{at0, at1}, {at0, at0}}), doctest::Contains("expected the same frames for every joint"),
                         error);
    CHECK_THROWS_WITH_AS(written({{at0}}), doctest::Contains("tracks of 1 joints: expected the hierarchy's 2"), error);
    CHECK_THROWS_WITH_AS(written({{at0}, {at0}, {at0}}), doctest::Contains("expected one track per joint"), error);
}

TEST_CASE("track_store: rows pushed track after track come back frame after frame, across blocks") {
    // Three tracks of 2,500 rows: blocks of rows in the file (made with the
    // first block written), and the one being filled.
    const std::size_t before = open_descriptors();
    track_store store(2);
    const std::size_t tracks = 3, rows = 2500;
    for (std::size_t t = 0; t < tracks; ++t) {
        store.begin_track();
        for (std::size_t i = 0; i < rows; ++i) {
            const double row[2] = {static_cast<double>(t), static_cast<double>(i)};
            store.push(row);
            if (t == 0 && i == 0) CHECK(open_descriptors() == before);
        }
    }
    CHECK(open_descriptors() == before + 1);
    REQUIRE(store.tracks() == tracks);
    bool same = true;
    for (std::size_t i = 0; i < rows; ++i)
        for (std::size_t t = 0; t < tracks; ++t) {
            REQUIRE(store.rows(t) == rows);
            const double* r = store.at(t, i);
            same = same && r[0] == static_cast<double>(t) && r[1] == static_cast<double>(i);
        }
    CHECK(same);
}

}  // namespace keyrot::test
