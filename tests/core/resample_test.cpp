// SPDX-License-Identifier: MIT
#include "keyrot/resample.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "helpers.hpp"

using namespace keyrot;
using keyrot::test::max_diff;
using keyrot::test::near;

namespace {

std::vector<sample> run(const track& t, resample_options opts = {}) {
    std::vector<sample> out;
    resample(t, opts, "test", [&](const sample& s) { out.push_back(s); });
    return out;
}

track keys_at(std::initializer_list<std::pair<double, quat>> list) {
    track t;
    for (const auto& [time, q] : list) t.keys.push_back(test::key_at(time, q));
    return t;
}

const double s45 = std::sqrt(0.5);

}  // namespace

TEST_CASE("frames lie on the absolute grid k / fps") {
    const auto out = run(keys_at({{0, quat{}}, {1, quat{s45, 0, 0, s45}}}));
    REQUIRE(out.size() == 25);
    for (std::size_t k = 0; k < out.size(); ++k) {
        CHECK(*out[k].frame == static_cast<double>(k));
        CHECK(out[k].time == static_cast<double>(k) / 24);  // never an accumulated sum
    }
    // keys off the grid: only the frames inside [0.01, 0.5]
    const auto inside = run(keys_at({{0.01, quat{}}, {0.5, quat{}}}));
    CHECK(*inside.front().frame == 1);
    CHECK(*inside.back().frame == 12);
    // a single key on the grid is one frame; off the grid, none
    CHECK(run(keys_at({{0.5, quat{}}})).size() == 1);
    CHECK(run(keys_at({{0.51, quat{}}})).empty());
}

TEST_CASE("a key within 1e-9 frame of the grid is on it") {
    const double t0 = 1.0 / 3.0 + 1e-12;  // frame 8 at 24 fps, a hair late
    const auto out = run(keys_at({{t0, quat{}}, {1, quat{}}}));
    CHECK(*out.front().frame == 8);
}

TEST_CASE("at a key time the output is that key, bit for bit") {
    keyrot::test::random_rotations rng(8);
    const quat a = rng.next(), b = rng.next(), c = rng.next();
    for (method m : {method::slerp, method::nlerp, method::squad, method::step}) {
        CAPTURE(to_string(m));
        const auto out = run(keys_at({{0, a}, {0.5, b}, {1.25, c}}), {24, m, path::direct});
        CHECK(out.size() == 31);
        // the output may be the key or its negation (sign continuity); never another value
        auto is_key = [](quat got, quat want) { return max_diff(got, want) == 0 || max_diff(got, -want) == 0; };
        CHECK(is_key(out[0].rotation, a));
        CHECK(is_key(out[12].rotation, b));
        CHECK(is_key(out[30].rotation, c));
    }
}

TEST_CASE("quaternion output is sign-continuous") {
    keyrot::test::random_rotations rng(12);
    track t;
    for (int i = 0; i < 8; ++i) {
        key k;
        k.time = i * 0.3;
        k.rotation = rng.next();
        t.keys.push_back(k);
    }
    for (path p : {path::shortest, path::direct}) {
        const auto out = run(t, {30, method::slerp, p});
        for (std::size_t i = 1; i < out.size(); ++i) CHECK(dot(out[i - 1].rotation, out[i].rotation) >= 0);
        CHECK(max_diff(out.front().rotation, t.keys.front().rotation) == 0);  // starts with the first key's sign
    }
}

TEST_CASE("turntable: a quarter turn a second, at 2 fps, 45 degrees a frame") {
    track t;
    for (int i = 0; i <= 4; ++i) {
        key k;
        k.time = i;
        k.rotation = exp(vec3{0, 0, i * std::numbers::pi / 4});
        t.keys.push_back(k);
    }
    const auto out = run(t, {2, method::slerp, path::shortest});
    REQUIRE(out.size() == 9);
    for (std::size_t i = 1; i < out.size(); ++i)
        CHECK(near(geodesic_angle(out[i - 1].rotation, out[i].rotation), std::numbers::pi / 4, 1e-15));
}

TEST_CASE("an absurd time range is an error, not an endless loop") {
    CHECK_THROWS_AS(run(keys_at({{0, quat{}}, {1e300, quat{}}})), input_error);
}

TEST_CASE("translation channel: linear between its own keys, held outside them") {
    track t = keys_at({{0, quat{}}, {1, quat{}}, {2, quat{}}, {3, quat{}}});
    t.keys[1].translation = vec3{0, 0, 0};
    t.keys[2].translation = vec3{2, 4, -6};
    const auto out = run(t, {4, method::slerp, path::shortest});
    REQUIRE(out.size() == 13);
    CHECK(out[0].translation->x == 0);   // before the first translation key: held
    CHECK(out[6].translation->y == 2);   // t = 1.5
    CHECK(out[5].translation->z == -1.5);  // t = 1.25
    CHECK(out[12].translation->x == 2);  // after the last: held
    const auto stepped = run(t, {4, method::step, path::shortest});
    CHECK(stepped[7].translation->x == 0);  // t = 1.75, held from t = 1
    CHECK_FALSE(run(keys_at({{0, quat{}}, {1, quat{}}}))[3].translation);
}

TEST_CASE("scale channel: its own keys, apart from the translation's, interpolated as the file says") {
    track t = keys_at({{0, quat{}}, {1, quat{}}, {2, quat{}}, {3, quat{}}});
    t.keys[0].translation = vec3{1, 1, 1};
    t.keys[3].translation = vec3{4, 4, 4};
    t.keys[1].scale = vec3{1, 2, 4};
    t.keys[2].scale = vec3{3, 2, 0};
    const auto out = run(t, {4, method::slerp, path::shortest});
    REQUIRE(out.size() == 13);
    CHECK(out[0].scale->y == 2);     // before the first scale key: held
    CHECK(out[6].scale->x == 2);     // t = 1.5: halfway
    CHECK(out[5].scale->z == 3);     // t = 1.25
    CHECK(out[12].scale->x == 3);    // after the last: held
    CHECK(out[6].translation->x == 2.5);  // the translation on its own keys meanwhile
    resample_options stepped_scale{4, method::slerp, path::shortest};
    stepped_scale.scale_how = method::step;
    const auto stepped = run(t, stepped_scale);
    CHECK(stepped[7].scale->x == 1);  // t = 1.75, held from t = 1
    CHECK(stepped[7].translation->x == 2.75);  // still linear
    CHECK_FALSE(run(keys_at({{0, quat{}}, {1, quat{}}}))[3].scale);
}

TEST_CASE("morph weights: component-wise linear, held by step, Hermite for cubicspline, on the rotation's grid") {
    // (a frame's weights are valid while it is handed over: kept here as copies)
    const auto weights = [](const track& t, const resample_options& opts) {
        std::vector<morph_weights> out;
        resample(t, opts, "test", [&](const sample& s) { out.emplace_back(s.weights.begin(), s.weights.end()); });
        return out;
    };
    track t = keys_at({{0, quat{}}, {1, quat{}}, {2, quat{}}});
    t.keys[0].weights = {0, 1};
    t.keys[1].weights = {1, 3};
    t.keys[2].weights = {0.5, -1};
    const auto out = weights(t, {4, method::slerp, path::shortest});
    REQUIRE(out.size() == 9);
    CHECK(out[1] == morph_weights{0.25, 1.5});  // t = 0.25
    CHECK(out[4] == morph_weights{1, 3});       // at the key
    CHECK(out[6] == morph_weights{0.75, 1});    // t = 1.5: halfway
    resample_options stepped{4, method::slerp, path::shortest};
    stepped.weights_how = method::step;
    CHECK(weights(t, stepped)[7] == morph_weights{1, 3});  // t = 1.75, held from t = 1
    // Hermite with the tangents below (per second, over a 1 s interval) at s = 1/2:
    // (v0 + v1) / 2 + (b0 - a1) / 8 for the first weight: (0 + 1) / 2 + (2 - 6) / 8 = 0.
    resample_options cubic{4, method::slerp, path::shortest};
    cubic.weights_how = method::cubicspline;
    full_spline_key first, second;
    first.weights_out = {2, 0}, second.weights_in = {6, 0};
    t.keys[0].spline = std::make_shared<const full_spline_key>(first);
    t.keys[1].spline = std::make_shared<const full_spline_key>(second);
    const auto curved = weights(t, cubic);
    CHECK(curved[2] == morph_weights{0, 2});  // the second weight's tangents are zero: halfway
    CHECK(weights(keys_at({{0, quat{}}, {1, quat{}}}), {})[2].empty());
}

TEST_CASE("streaming: frames come out as keys arrive, squad one key behind") {
    track t = keys_at({{0, quat{}}, {0.5, exp(vec3{0, 0, 0.2})}, {1, exp(vec3{0, 0.3, 0})}, {1.5, quat{}}});
    for (method m : {method::slerp, method::squad}) {
        CAPTURE(to_string(m));
        std::vector<sample> got;
        track_resampler r({4, m, path::shortest}, std::nullopt, channels{}, [&](const sample& s) { got.push_back(s); });
        std::vector<std::size_t> after;
        for (const key& k : t.keys) {
            r.add(k);
            after.push_back(got.size());
        }
        r.finish();
        // slerp: the frames before key i once key i has arrived; squad waits for key i+1
        CHECK(after == (m == method::slerp ? std::vector<std::size_t>{0, 2, 4, 6} : std::vector<std::size_t>{0, 0, 2, 4}));
        CHECK(got.size() == 7);
        // the same frames as the whole-track path
        const auto whole = run(t, {4, m, path::shortest});
        for (std::size_t i = 0; i < got.size(); ++i) CHECK(max_diff(got[i].rotation, whole[i].rotation) == 0);
    }
}
