// SPDX-License-Identifier: MIT
#include "io/common/raw_key.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <sstream>

#include "helpers.hpp"

using namespace keyrot;
using keyrot::test::max_diff;

namespace {

/// A track's header and raw keys, as a reader hands them to track_builder.
struct given_track : raw_track {
    std::vector<raw_key> keys;
};

track build(const given_track& t, warnings& warn) {
    track_builder b(t.name, t.at, t.settings);
    for (const raw_key& k : t.keys) b.add(k, warn);
    return std::move(b).finish(warn);
}

raw_key raw(double time, rep kind, std::initializer_list<double> values) {
    raw_key k;
    k.at.line = 2;
    k.time = time;
    k.kind = kind;
    std::copy(values.begin(), values.end(), k.values.begin());
    return k;
}

std::string error_of(const given_track& t) {
    std::ostringstream err;
    warnings warn(err, "t.csv");
    try {
        build(t, warn);
    } catch (const input_error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("every input representation becomes the same unit quaternion") {
    const double s = std::sqrt(0.5);
    const quat want{s, 0, 0, s};  // 90 degrees about z
    given_track t;
    t.settings.euler = parse_euler_seq("ZYX");
    t.keys = {raw(0, rep::quat, {2 * s, 0, 0, 2 * s}),  // norm 2: normalised
              raw(1, rep::axis_angle, {0, 0, 3, 90}), raw(2, rep::rotvec, {0, 0, 90}),
              raw(3, rep::euler, {90, 0, 0}), raw(4, rep::matrix, {0, -1, 0, 1, 0, 0, 0, 0, 1}),
              raw(5, rep::matrix4, {0, -1, 0, 7, 1, 0, 0, 8, 0, 0, 1, 9, 0, 0, 0, 1})};
    std::ostringstream err;
    warnings warn(err, "t.csv");
    const track out = build(t, warn);
    for (const key& k : out.keys) {
        CAPTURE(k.time);
        CHECK(max_diff(k.rotation, want) <= 2e-16);
    }
    CHECK(out.keys[0].renormalised);
    CHECK(err.str().find("keyrot: warning: t.csv: quaternion norm 2") == 0);
    CHECK(out.keys[5].translation->z == 9);
    // each key's values as given, in the file's unit, but a matrix's
    CHECK(out.keys[0].given->values == std::array<double, 4>{2 * s, 0, 0, 2 * s});
    CHECK(out.keys[1].given->values == std::array<double, 4>{0, 0, 3, 90});
    CHECK(out.keys[3].given->values[0] == 90);
    CHECK(out.keys[3].given->unit == angle_unit::degrees);
    CHECK(!out.keys[4].given);
    CHECK(!out.keys[5].given);
}

TEST_CASE("radians and frames") {
    given_track t;
    t.settings.angles = angle_unit::radians;
    t.settings.key_fps = 30;
    raw_key k = raw(0, rep::axis_angle, {1, 0, 0, std::numbers::pi});
    k.time.reset();
    k.frame = 15;
    t.keys = {k};
    std::ostringstream err;
    warnings warn(err, "x");
    const track out = build(t, warn);
    CHECK(out.keys[0].time == 0.5);
    CHECK(*out.keys[0].frame == 15);
    CHECK(std::fabs(out.keys[0].rotation.x - 1) <= 1e-16);
}

TEST_CASE("validation errors name the key and what was expected") {
    given_track t;
    t.keys = {raw(0, rep::quat, {0, 0, 0, 0})};
    CHECK(error_of(t) == "t.csv:2: quaternion is zero: expected a non-zero quaternion");
    t.keys = {raw(0, rep::axis_angle, {0, 0, 0, 10})};
    CHECK(error_of(t).find("axis is zero") != std::string::npos);
    t.keys = {raw(0, rep::axis_angle, {0, 0, 0, 0})};  // zero axis with zero angle: the identity
    CHECK(error_of(t).empty());
    t.keys = {raw(0, rep::matrix, {2, 0, 0, 0, 2, 0, 0, 0, 2})};
    CHECK(error_of(t).find("matrix is not a rotation") != std::string::npos);
    t.keys = {raw(0, rep::matrix, {1, 0, 0, 0, 1, 0, 0, 0, -1})};
    CHECK(error_of(t).find("determinant") != std::string::npos);
    t.keys = {raw(0, rep::matrix, {1, 0.1, 0, 0, 1, 0, 0, 0, 1})};  // sheared
    CHECK(error_of(t).find("not a rotation") != std::string::npos);
    t.keys = {raw(0, rep::euler, {1, 2, 3})};
    CHECK(error_of(t).find("Euler angles need a sequence") != std::string::npos);
    t.keys = {raw(1, rep::quat, {1, 0, 0, 0}), raw(1, rep::quat, {1, 0, 0, 0})};
    CHECK(error_of(t).find("not after the previous key") != std::string::npos);
    t.keys = {raw(1, rep::quat, {1, 0, 0, 0}), raw(0.5, rep::quat, {1, 0, 0, 0})};
    CHECK(error_of(t).find("strictly increasing") != std::string::npos);
    t.keys = {};
    t.at.path = "keys";
    CHECK(error_of(t) == "t.csv: keys: no keys: expected at least one key");
}

TEST_CASE("a frame of keyrot's output, made at any rate, is timed by its time") {
    given_track t;
    raw_key both = raw(0.25, rep::quat, {1, 0, 0, 0});
    both.frame = 1;  // made at 4 fps; the key rate is 24
    t.keys = {both};
    std::ostringstream err;
    warnings warn(err, "x");
    const track out = build(t, warn);
    CHECK(out.keys[0].time == 0.25);
    CHECK(*out.keys[0].frame == 1);
}

TEST_CASE("--strict makes a non-unit quaternion an error") {
    given_track t;
    t.settings.strict = true;
    t.keys = {raw(0, rep::quat, {1.01, 0, 0, 0})};
    CHECK(error_of(t).find("--strict") != std::string::npos);
    t.keys = {raw(0, rep::quat, {1.0001, 0, 0, 0})};  // within 1e-3: accepted quietly
    CHECK(error_of(t).empty());
}
