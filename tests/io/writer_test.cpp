// SPDX-License-Identifier: MIT
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

TEST_CASE("outputs are plain: the names of the columns and members say the unit and the order") {
    const std::vector<table_row> rows = {{{0.5, 12.0, quat{}, std::nullopt}}};
    table_info frames;  // resample's: frames with their times
    frames.fps = 30;
    frames.method = "slerp";
    table_info keys = frames;  // convert's: each key's time, and its frame where it has one
    keys.times = time_columns::as_given;
    keys.any_frame = true;
    write_options w;
    w.representation = rep::rotvec;
    const auto first_line = [&](format f, const table_info& info, const std::vector<table_row>& table) {
        const std::string text = write(f, info, w, table);
        return text.substr(0, text.find('\n'));
    };
    const auto first = [&](format f, const table_info& info) { return first_line(f, info, rows); };
    // degrees, the default: plain names; a time on every row, frames or keys
    CHECK(first(format::csv, frames) == "frame,time,rx,ry,rz");
    CHECK(first(format::csv, keys) == "frame,time,rx,ry,rz");
    CHECK(first(format::ndjson, keys) == R"({"frame": 12, "time": 0.5, "rotvec": [0, 0, 0]})");
    // a key of a time alone beside keys of frames: an empty frame cell, no frame member
    const std::vector<table_row> timed = {{{0.25, std::nullopt, quat{}, std::nullopt}}};
    CHECK(write(format::csv, keys, w, timed) == "frame,time,rx,ry,rz\n,0.25,0,0,0\n");
    CHECK(first_line(format::ndjson, keys, timed) == R"({"time": 0.25, "rotvec": [0, 0, 0]})");
    // radians: in the names of the angles' columns and members, velocities' too
    w.angles = angle_unit::radians;
    CHECK(first(format::csv, frames) == "frame,time,rx_rad,ry_rad,rz_rad");
    CHECK(first(format::ndjson, frames) == R"({"frame": 12, "time": 0.5, "rotvec_rad": [0, 0, 0]})");
    w.representation = rep::axis_angle;
    table_info rated = frames;
    rated.velocity = rated.acceleration = true;
    CHECK(first(format::csv, rated) == "frame,time,ax,ay,az,angle_rad,wx_rad,wy_rad,wz_rad,dwx_rad,dwy_rad,dwz_rad");
    CHECK(first(format::ndjson, frames) == R"({"frame": 12, "time": 0.5, "axis": [1, 0, 0], "angle_rad": 0})");
    w.representation = rep::euler;
    w.euler = parse_euler_seq("ZYX");
    CHECK(first(format::csv, frames) == "frame,time,e1_rad,e2_rad,e3_rad");
    CHECK(first(format::ndjson, frames) == R"({"frame": 12, "time": 0.5, "euler_rad": [0, 0, 0]})");
    // a JSON document states them as its fields, and keeps the plain names
    CHECK(write(format::json, frames, w, rows) ==
          "{\"fps\": 30, \"method\": \"slerp\", \"rep\": \"euler\", \"angles\": \"radians\", \"euler\": \"ZYX\", \"frames\": [\n"
          "{\"frame\": 12, \"time\": 0.5, \"euler\": [0, 0, 0]}]}\n");
    // quaternion arrays in xyzw order: NDJSON says so in the name, CSV names its columns
    w.representation = rep::quat;
    w.order = quat_order::xyzw;
    CHECK(first(format::csv, frames) == "frame,time,qx,qy,qz,qw");
    CHECK(first(format::ndjson, frames) == R"({"frame": 12, "time": 0.5, "quat_xyzw": [0, 0, 0, 1]})");
    // the settings line only when asked, with every setting
    w.states = settings_line::always;
    CHECK(first(format::csv, frames) ==
          R"(# keyrot {"fps": 30, "method": "slerp", "rep": "quat", "angles": "radians", "quat_order": "xyzw"})");
    CHECK(first(format::ndjson, frames) ==
          R"({"fps": 30, "method": "slerp", "rep": "quat", "angles": "radians", "quat_order": "xyzw"})");
}

TEST_CASE("the names that state a unit or an order read back as they say") {
    const double s = std::sqrt(0.5);
    read_options o;
    o.settings.euler = parse_euler_seq("ZYX");
    const auto only_key = [&](std::string_view text, format f) { return read(std::string(text), f, o).tracks.at(0).keys.at(0); };
    const quat quarter_z{s, 0, 0, s};
    // (a named pair, not a structured binding: CAPTURE's lambda cannot take one in clang 14)
    for (const auto& text_in : std::vector<std::pair<std::string, format>>{
             {"time,ax,ay,az,angle_rad\n0,0,0,1,1.5707963267948966\n", format::csv},
             {"time,rx_deg,ry_deg,rz_deg\n0,0,0,90\n", format::csv},
             {"time,e1_rad,e2_rad,e3_rad\n0,1.5707963267948966,0,0\n", format::csv},
             {R"({"time": 0, "axis": [0, 0, 1], "angle_rad": 1.5707963267948966})", format::ndjson},
             {R"({"time": 0, "euler_rad": [1.5707963267948966, 0, 0]})", format::ndjson},
             {R"({"time": 0, "quat_xyzw": [0, 0, 0.7071067811865476, 0.7071067811865476]})", format::ndjson},
             {R"({"keys": [{"time": 0, "rotvec_rad": [0, 0, 1.5707963267948966]}]})", format::json}}) {
        CAPTURE(text_in.first);
        CHECK(keyrot::test::same_rotation(only_key(text_in.first, text_in.second).rotation, quarter_z, 1e-15));
    }
    // a unit stated by one angle's name is stated by all, and one unit at that
    for (const auto& text_in : std::vector<std::pair<std::string, format>>{
             {"time,ax,ay,az,angle_rad,wx,wy,wz\n0,0,0,1,1,0,0,0\n", format::csv},
             {"time,ax,ay,az,angle_rad,wx_deg,wy_deg,wz_deg\n0,0,0,1,1,0,0,0\n", format::csv},
             {R"({"time": 0, "axis": [0, 0, 1], "angle_rad": 1, "angular_velocity": [0, 0, 0]})", format::ndjson},
             {R"({"time": 0, "quat": [1, 0, 0, 0], "quat_xyzw": [0, 0, 0, 1]})", format::ndjson}}) {
        CAPTURE(text_in.first);
        CHECK_THROWS_AS(only_key(text_in.first, text_in.second), input_error);
    }
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

