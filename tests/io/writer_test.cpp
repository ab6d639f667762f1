// Writing CSV, JSON and NDJSON tables, and reading them back.
#include "io/common/interface.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <sstream>

#include "helpers.hpp"
#include "reading.hpp"

using namespace keyrot;
using keyrot::test::read;
using keyrot::test::write;

TEST_CASE("writers: CSV, JSON and NDJSON tables") {
    const double s = std::sqrt(0.5);
    const std::vector<table_row> rows = {{{0, 0.0, quat{}, vec3{1, 2, 3}}}, {{0.5, 12.0, quat{s, 0, 0, s}, vec3{0, 0, -1}}}};
    table_info info;
    info.carried.translation = true;
    info.fps = 24;
    info.method = "slerp";
    write_options w;
    w.representation = rep::quat;
    w.precision = 4;
    // --precision rounds the values, not the times
    CHECK(write(format::csv, info, w, rows) ==
          "frame,time,qw,qx,qy,qz,tx,ty,tz\n0,0,1,0,0,0,1,2,3\n12,0.5,0.7071,0,0,0.7071,0,0,-1\n");
    CHECK(write(format::json, info, w, rows) ==
          "{\"fps\": 24, \"method\": \"slerp\", \"rep\": \"quat\", \"angles\": \"degrees\", \"quat_order\": \"wxyz\", "
          "\"frames\": [\n"
          "{\"frame\": 0, \"time\": 0, \"quat\": [1, 0, 0, 0], \"translation\": [1, 2, 3]},\n"
          "{\"frame\": 12, \"time\": 0.5, \"quat\": [0.7071, 0, 0, 0.7071], \"translation\": [0, 0, -1]}]}\n");
    info.named = true;
    w.representation = rep::axis_angle;
    CHECK(write(format::ndjson, info, w, rows, "hip") ==
          "{\"track\": \"hip\", \"frame\": 0, \"time\": 0, \"axis\": [1, 0, 0], \"angle\": 0, \"translation\": [1, 2, 3]}\n"
          "{\"track\": \"hip\", \"frame\": 12, \"time\": 0.5, \"axis\": [0, 0, 1], \"angle\": 90, \"translation\": [0, 0, -1]}\n");
    CHECK(write(format::csv, info, w, rows, "a,b").find("\"a,b\",0,0,1,0,0,0,1,2,3\n") != std::string::npos);
}

TEST_CASE("a settings line only where keyrot would otherwise misread the rows") {
    const std::vector<table_row> rows = {{{0.5, 12.0, quat{}, std::nullopt}}};
    table_info frames;  // resample's: frames with their times
    frames.fps = 30;
    frames.method = "slerp";
    table_info keys = frames;  // convert's: frame numbers alone
    keys.times = time_columns::as_given;
    keys.all_frames = true;
    keys.any_time = false;
    keys.counted = true;
    write_options w;
    w.representation = rep::rotvec;
    const std::vector<table_row> counted_rows = {{{0.5, 12.0, quat{}, std::nullopt}, false}};
    const auto first_line = [&](format f, const table_info& info) {
        const std::string text = write(f, info, w, info.counted ? counted_rows : rows);
        return text.substr(0, text.find('\n'));
    };
    for (format f : {format::csv, format::ndjson}) {
        CAPTURE(to_string(f));
        const std::string plain = f == format::csv ? "frame,time,rx,ry,rz" : "{\"frame\": 12, \"time\": 0.5, \"rotvec\": [0, 0, 0]}";
        const std::string line = f == format::csv ? "# keyrot {{{}}}" : "{{{}}}";
        w.angles = angle_unit::degrees;
        CHECK(first_line(f, frames) == plain);
        CHECK(first_line(f, keys) == fmt::format(fmt::runtime(line), "\"fps\": 30"));
        w.angles = angle_unit::radians;
        CHECK(first_line(f, frames) == fmt::format(fmt::runtime(line), "\"angles\": \"radians\""));
        w.states = settings_line::always;
        CHECK(first_line(f, frames) == fmt::format(fmt::runtime(line), "\"fps\": 30, \"method\": \"slerp\", \"rep\": \"rotvec\", \"angles\": \"radians\""));
        w.states = settings_line::never;
        CHECK(first_line(f, keys) == (f == format::csv ? "frame,rx,ry,rz" : "{\"frame\": 12, \"rotvec\": [0, 0, 0]}"));
        w.states = settings_line::needed;
    }
    // quaternion arrays in xyzw order: NDJSON says so, CSV names its columns
    w.angles = angle_unit::radians;  // (no angles in a quaternion)
    w.representation = rep::quat;
    w.order = quat_order::xyzw;
    CHECK(first_line(format::csv, frames) == "frame,time,qx,qy,qz,qw");
    CHECK(first_line(format::ndjson, frames) == "{\"quat_order\": \"xyzw\"}");
    // an Euler sequence is never needed: read without one, it is refused
    w.representation = rep::euler;
    w.euler = parse_euler_seq("ZYX");
    w.angles = angle_unit::degrees;
    CHECK(first_line(format::ndjson, frames).starts_with("{\"frame\": 12"));
    // a JSON document states everything, as fields
    CHECK(first_line(format::json, frames) ==
          "{\"fps\": 30, \"method\": \"slerp\", \"rep\": \"euler\", \"angles\": \"degrees\", \"euler\": \"ZYX\", \"frames\": [");
}

TEST_CASE("keyrot reads what it writes, in every format and representation") {
    keyrot::test::random_rotations rng(77);
    std::vector<table_row> rows;
    for (int i = 0; i < 5; ++i) rows.push_back({{i / 24.0, static_cast<double>(i), rng.next(), vec3{0.5 * i, 1, 2}}});
    table_info info;
    info.carried.translation = true;
    info.fps = 24;
    for (format f : {format::csv, format::json, format::ndjson}) {
        for (const auto& named : names_of<rep>) {
            write_options w;
            w.representation = named.value;
            w.euler = parse_euler_seq("yxz");
            CAPTURE(to_string(f));
            CAPTURE(named.name);
            const std::string text = write(f, info, w, rows);
            read_options o;
            o.settings.euler = w.euler;
            const track t = read(text, f, o).tracks.at(0);
            REQUIRE(t.keys.size() == rows.size());
            for (std::size_t i = 0; i < rows.size(); ++i) {
                CHECK(keyrot::test::same_rotation(t.keys[i].rotation, rows[i].rotation, 1e-15));
                CHECK(t.keys[i].time == rows[i].time);
                CHECK(std::fabs(t.keys[i].translation->x - rows[i].translation->x) <= 1e-15);
            }
        }
    }
}

