// SPDX-License-Identifier: MIT
#include "keyrot/compare.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "helpers.hpp"

using namespace keyrot;

namespace {

key at(double time, quat q, std::optional<double> frame = std::nullopt) { return test::key_at(time, q, frame); }

track named(std::string name, std::vector<key> keys) { return track{std::move(name), std::nullopt, std::move(keys), std::nullopt}; }

}  // namespace

TEST_CASE("q and -q are the same answer") {
    keyrot::test::random_rotations rng(1);
    const quat a = rng.next(), b = rng.next();
    const auto c = compare_tracks({named("", {at(0, a), at(1, b)})}, {named("", {at(0, -a), at(1, -b)})}, {});
    CHECK(c.failed == 0);
    CHECK(c.rows.size() == 2);
    CHECK(*c.worst->angle_deg <= 1e-6);
}

TEST_CASE("an answer half a degree off at one frame fails there") {
    const quat off = exp(vec3{0, 0, 0.25 * std::numbers::pi / 180});  // 0.5 degrees about z
    const auto c = compare_tracks({named("", {at(0, quat{}, 0), at(0.5, quat{}, 12)})},
                                  {named("", {at(0, quat{}, 0), at(0.5, off, 12)})}, {});
    CHECK(c.failed == 1);
    REQUIRE(c.worst);
    CHECK(*c.worst->frame == 12);
    CHECK(std::fabs(*c.worst->angle_deg - 0.5) <= 1e-12);
    CHECK(c.rows[1].problem == "rotation differs by 0.5 deg (tolerance 0.01)");
    const auto loose = compare_tracks({named("", {at(0.5, quat{}, 12)})}, {named("", {at(0.5, off, 12)})}, {1, 0.001});
    CHECK(loose.failed == 0);
}

TEST_CASE("rows are matched by frame when both have one, else by time") {
    // the frame matches although the times were written with different rounding
    auto c = compare_tracks({named("", {at(0.041666, quat{}, 1)})}, {named("", {at(0.0417, quat{}, 1)})}, {});
    CHECK(c.failed == 0);
    c = compare_tracks({named("", {at(0.5, quat{})})}, {named("", {at(0.5000005, quat{}, 12)})}, {});
    CHECK(c.failed == 0);  // within 1e-6 s
    c = compare_tracks({named("", {at(0.5, quat{})})}, {named("", {at(0.50001, quat{})})}, {});
    CHECK(c.failed == 2);  // one missing from the answer, one only in the answer
    CHECK(c.rows[0].problem == "missing from the answer");
    CHECK(c.rows[1].problem == "only in the answer");
}

TEST_CASE("frames that carry their times are matched by frame only where the grids agree") {
    // keyrot's resampled frames state no rate: 4 fps against 8 fps, whose frame 1 is 0.25 s against 0.125 s
    const quat turned = exp(vec3{0, 0, 0.1});
    std::vector<key> four, eight;
    for (int f = 0; f <= 4; ++f) four.push_back(at(f / 4.0, exp(vec3{0, 0, 0.1 * f / 4.0}), f));
    for (int f = 0; f <= 8; ++f) eight.push_back(at(f / 8.0, exp(vec3{0, 0, 0.1 * f / 8.0}), f));
    auto c = compare_tracks({named("", four)}, {named("", eight)}, {});
    REQUIRE(c.frame_rates);
    CHECK(c.frame_rates->first == 4);
    CHECK(c.frame_rates->second == 8);
    CHECK(c.failed == 4);  // the 4 frames of 8 fps between the 4 fps ones
    CHECK(c.rows.size() == 9);
    CHECK(std::count_if(c.rows.begin(), c.rows.end(), [](const auto& r) { return r.problem == "only in the answer"; }) == 4);
    // at one rate, times written to four decimals still match by frame
    c = compare_tracks({named("", {at(1 / 24.0, turned, 1), at(2, turned, 48)})},
                       {named("", {at(0.0417, turned, 1), at(2, turned, 48)})}, {});
    CHECK(c.failed == 0);
    CHECK(!c.frame_rates);
    // and frames without times count at the rate stated, exactly
    key k24 = at(1 / 24.0, turned, 1), k30 = at(1 / 30.0, turned, 1);
    k24.has_time = k30.has_time = false;
    track t30 = named("", {k30});
    t30.key_fps = 30;
    c = compare_tracks({named("", {k24})}, {t30}, {});
    CHECK(c.failed == 2);
    CHECK(counted_rate(t30) == 30);
}

TEST_CASE("tracks are matched by name; translations are checked when expected") {
    key with_t = at(0, quat{});
    with_t.translation = vec3{1, 2, 3};
    key close_t = with_t;
    close_t.translation = vec3{1, 2, 3.0005};
    key far_t = with_t;
    far_t.translation = vec3{1, 2, 3.01};
    CHECK(compare_tracks({named("hip", {with_t})}, {named("hip", {close_t})}, {}).failed == 0);
    CHECK(compare_tracks({named("hip", {with_t})}, {named("hip", {far_t})}, {}).failed == 1);
    CHECK(compare_tracks({named("hip", {with_t})}, {named("hip", {at(0, quat{})})}, {}).rows[0].problem ==
          "translation missing from the answer");
    CHECK(compare_tracks({named("hip", {with_t})}, {named("knee", {with_t})}, {}).failed == 2);
    key scaled = with_t, rescaled = with_t;
    scaled.scale = vec3{1, 1, 1};
    rescaled.scale = vec3{1, 1, 1.01};
    CHECK(compare_tracks({named("hip", {scaled})}, {named("hip", {rescaled})}, {}).rows[0].problem ==
          "scale differs by 0.01 (tolerance 0.001)");
    CHECK(compare_tracks({named("hip", {scaled})}, {named("hip", {with_t})}, {}).rows[0].problem ==
          "scale missing from the answer");
    CHECK(compare_tracks({named("hip", {with_t})}, {named("hip", {rescaled})}, {}).failed == 0);
    const quat turned = exp(vec3{0, 0, 0.5});
    const auto reordered = compare_tracks({named("hip", {with_t}), named("knee", {at(0, turned)})},
                                          {named("knee", {at(0, turned)}), named("hip", {with_t})}, {});
    CHECK(reordered.failed == 0);
    CHECK(reordered.rows.size() == 2);
    // one unnamed track against one named track (a glTF file names its node): the same track
    const auto renamed = compare_tracks({named("", {with_t})}, {named("track", {with_t})}, {});
    CHECK(renamed.failed == 0);
    CHECK(renamed.matched == 1);
    CHECK(renamed.rows.at(0).track.empty());
    CHECK(compare_tracks({named("hip", {with_t})}, {named("", {far_t})}, {}).failed == 1);  // (compared: 0.01 off)
    // but two named tracks, or more than one track, are paired by name
    CHECK(compare_tracks({named("hip", {with_t})}, {named("knee", {with_t})}, {}).matched == 0);
    CHECK(compare_tracks({named("", {with_t}), named("b", {with_t})}, {named("a", {with_t})}, {}).matched == 0);
}

TEST_CASE("each key matches the key a scan of the answer would find") {
    // The reference is the plain scan: the key of the answer with the same frame
    // when both have one, else within 1e-6 s. Keys lie near a 24 fps grid,
    // some by frame number alone, some by a time up to 3 us off the grid,
    // so near misses and exact 1e-6 steps are common; each answer key has
    // its own angle, so a row's angle tells which key it matched.
    const auto scan = [](const std::vector<key>& keys, const key& k) -> std::optional<std::size_t> {
        for (std::size_t i = 0; i < keys.size(); ++i) {
            const key& other = keys[i];
            if (k.frame && other.frame ? *k.frame == *other.frame : std::fabs(k.time - other.time) <= 1e-6) return i;
        }
        return std::nullopt;
    };
    std::mt19937 gen(7);
    std::uniform_int_distribution<int> gap(1, 2), jitter(-3, 3), coin(0, 1);
    const auto random_keys = [&](bool distinct_angles) {
        std::vector<key> keys;
        int f = 0;
        for (int i = 0; i < 80; ++i) {
            f += gap(gen);
            const quat q = distinct_angles ? exp(vec3{0, 0, 1e-3 * (i + 1)}) : quat{};
            if (coin(gen)) {
                keys.push_back(at(f / 24.0, q, f));  // a frame counted at the default rate
                keys.back().has_time = false;
            } else {
                keys.push_back(at(f / 24.0 + jitter(gen) * 1e-6, q));
            }
        }
        return keys;
    };
    std::size_t matched = 0, unmatched_rows = 0;
    for (int round = 0; round < 300; ++round) {
        const std::vector<key> expected = random_keys(false), actual = random_keys(true);
        const auto c = compare_tracks({named("", expected)}, {named("", actual)}, {1e9, 1});
        std::vector<bool> used(actual.size());
        std::size_t row = 0;
        for (std::size_t i = 0; i < expected.size(); ++i) {
            CAPTURE(round);
            CAPTURE(i);
            const auto j = scan(actual, expected[i]);
            // the rows come in time order: the expected key's, after the answer's own before it
            while (row < c.rows.size() && c.rows[row].extra) ++row;
            REQUIRE(row < c.rows.size());
            CHECK(c.rows[row].time == expected[i].time);
            REQUIRE(c.rows[row].angle_deg.has_value() == j.has_value());
            if (j) {
                used[*j] = true;
                ++matched;
                CHECK(*c.rows[row].angle_deg ==
                      from_radians(geodesic_angle(quat{}, actual[*j].rotation), angle_unit::degrees));
            }
            ++row;
        }
        const auto only_in_actual = static_cast<std::size_t>(std::count(used.begin(), used.end(), false));
        CHECK(c.rows.size() == expected.size() + only_in_actual);
        CHECK(c.extra == only_in_actual);
        unmatched_rows += c.rows.size() - expected.size();
        CHECK(std::is_sorted(c.rows.begin(), c.rows.end(), [](const auto& a, const auto& b) { return a.time < b.time; }));
    }
    CHECK(matched > 1000);  // the cases are not all misses
    CHECK(unmatched_rows > 1000);
}
