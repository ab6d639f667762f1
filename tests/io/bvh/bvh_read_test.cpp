// The two readers of a BVH file give the same keys, joint after joint or
// frame after frame, and stop at the same error; bvh_output writes a frame
// once every joint has it.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "io/bvh/bvh_read.hpp"
#include "io/bvh/bvh_write.hpp"
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

/// Each track's keys as the reader made by `make` gives them.
template <typename Make>
std::pair<std::map<std::string, std::vector<raw_key>>, std::string> by_track(
    const std::string& text, Make make, std::vector<std::string>* order = nullptr) {
    std::istringstream in(text);
    const auto reader = make(in, take_options());
    const reading_result r = read_all(*reader);
    std::map<std::string, std::vector<raw_key>> tracks;
    for (const auto& [name, k] : r.keys) {
        tracks[name].push_back(k);
        if (order) order->push_back(name);
    }
    return {tracks, r.error};
}

void check_same(const raw_key& a, const raw_key& b) {
    CHECK(a.at.line == b.at.line);
    CHECK(a.frame == b.frame);
    CHECK(a.kind == b.kind);
    CHECK(a.values == b.values);
    CHECK(a.translation.has_value() == b.translation.has_value());
    if (a.translation && b.translation) {
        CHECK(a.translation->x == b.translation->x);
        CHECK(a.translation->z == b.translation->z);
    }
}

}  // namespace

TEST_CASE("BVH: the frame reader gives the column reader's keys, frame after frame") {
    std::vector<std::string> order;
    const auto [columns, none] = by_track(take, make_bvh_reader);
    const auto [frames, also_none] = by_track(take, make_bvh_frame_reader, &order);
    CHECK(none.empty());
    CHECK(also_none.empty());
    CHECK(order == std::vector<std::string>{"Hips", "Leg", "Hips", "Leg", "Hips", "Leg"});
    REQUIRE(columns.size() == 2);
    for (const auto& [name, keys] : columns) {
        REQUIRE(frames.at(name).size() == 3);
        for (std::size_t i = 0; i < keys.size(); ++i) check_same(keys[i], frames.at(name)[i]);
    }
    const raw_key& leg = frames.at("Leg")[2];
    CHECK(leg.at.line == 22);     // after the blank line
    CHECK(leg.values[0] == -40);  // Yrotation first: the sequence YXZ
    CHECK(frames.at("Hips")[1].translation->y == 2);
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
    for (const bool frame_major : {false, true}) {
        CAPTURE(frame_major);
        std::vector<std::string> order;
        const auto [tracks, error] = frame_major ? by_track(text, make_bvh_frame_reader, &order)
                                                 : by_track(text, make_bvh_reader, &order);
        CHECK(error.empty());
        std::vector<std::string> names;  // in order of first appearance
        for (const std::string& name : order)
            if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
        CHECK(names == std::vector<std::string>{"Hips", "Leg", "Leg.2", "Leg.2.2", "Leg.3"});
        CHECK(tracks.size() == 5);
    }
}

TEST_CASE("BVH: both readers stop at the same error, after the same keys") {
    for (const auto& bad : std::vector<std::pair<std::string, std::string>>{
             {take.substr(0, take.size() - 4) + "\n",
              "take.bvh:22: expected 9 values (the hierarchy's channels), got 8"},
             {take + "1 1 1 1 1 1 1 1 1\n", "take.bvh:23: a frame line after the 3 that 'Frames:' states"},
             {take.substr(0, take.rfind("4 5 6")), "'Frames: 3', but 2 frame lines"}}) {
        const std::string& text = bad.first;
        const std::string& message = bad.second;  // (not a structured binding: clang's lambdas in the checks)
        CAPTURE(message);
        const auto columns = by_track(text, make_bvh_reader).second;
        const auto frames = by_track(text, make_bvh_frame_reader).second;
        CHECK(columns.find(message) != std::string::npos);
        CHECK(frames == columns);
        std::istringstream in(text);
        CHECK_THROWS_WITH_AS(check_bvh_frames(in, take_options()), doctest::Contains(message.c_str()), input_error);
    }
}

TEST_CASE("bvh_output: a frame line once every joint has its row, in its channel order") {
    std::ostringstream out;
    bvh_output file(std::nullopt, out, take_source(), 2, 0.5, {});
    const auto row = [](double time, quat q, vec3 position) {
        sample s;
        s.time = time;
        s.rotation = q;
        s.translation = position;
        return s;
    };
    const quat z90{std::sqrt(0.5), 0, 0, std::sqrt(0.5)};  // 90 degrees about z
    // Hips runs a frame ahead of Leg: nothing is written before Leg's frame 0.
    file.row(0, row(0, z90, {1, 2, 3}));
    file.row(0, row(0.5, quat{1, 0, 0, 0}, {4, 5, 6}));
    file.row(1, row(0, z90, {}));
    file.row(1, row(0.5, -z90, {}));
    file.finish();
    const std::string text = out.str();
    REQUIRE(text.rfind("MOTION\nFrames: 2\nFrame Time: 0.5\n") != std::string::npos);
    const std::string motion = text.substr(text.rfind("Frame Time: 0.5\n") + 16);
    // Hips: ZXY, positions first; Leg: YXZ, so z is its third channel. -q is q.
    CHECK(motion == "1 2 3 90 0 0 0 0 90\n4 5 6 0 0 0 0 0 90\n");
    CHECK(text.substr(0, text.find("MOTION")) == take.substr(0, take.find("MOTION")));
}

TEST_CASE("bvh_output: rows that do not make the frames stated are an error") {
    std::ostringstream out;
    bvh_output file(std::nullopt, out, take_source(), 2, 0.5, {});
    sample s;
    file.row(0, s);
    file.row(1, s);
    CHECK_THROWS_AS(file.finish(), error);
    sample later;
    later.time = 1;
    file.row(0, s);
    CHECK_THROWS_WITH_AS(file.row(1, later), doctest::Contains("expected the same frames for every joint"), error);
}

}  // namespace keyrot::test
