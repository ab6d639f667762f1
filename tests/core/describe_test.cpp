// SPDX-License-Identifier: MIT
#include "keyrot/describe.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "helpers.hpp"

using namespace keyrot;

TEST_CASE("segments, flips, renormalised and near-gimbal keys") {
    const double s = std::sqrt(0.5);
    track t;
    t.euler = parse_euler_seq("ZYX");
    auto add = [&t](double time, quat q) {
        t.keys.push_back(test::key_at(time, q));
        return &t.keys.back();
    };
    add(0, quat{});
    add(0.5, quat{-s, 0, 0, -s});                 // 90 about z, written in the other hemisphere
    add(1.5, quat{0, 0, 0, 1})->renormalised = true;  // 180 about z
    key* e = add(2, from_euler({0.3, std::numbers::pi / 2 - 0.01, 0}, *t.euler));
    e->given_as = rep::euler;
    e->given = given_rotation{{0.3, std::numbers::pi / 2 - 0.01, 0, 0}, angle_unit::radians};
    const track_info info = describe(t);
    CHECK(info.keys == 4);
    CHECK(info.start == 0);
    CHECK(info.end == 2);
    REQUIRE(info.segments.size() == 3);
    CHECK(std::fabs(info.segments[0].angle_deg - 90) <= 1e-12);
    CHECK(std::fabs(info.segments[0].speed_deg_s - 180) <= 1e-12);
    CHECK(info.segments[0].direct_long_way);
    CHECK(std::fabs(info.segments[1].angle_deg - 90) <= 1e-12);
    CHECK(info.flipped.first == std::vector<std::size_t>{1, 2});  // each against the one before
    CHECK(info.renormalised.first == std::vector<std::size_t>{2});
    CHECK(info.near_gimbal.first == std::vector<std::size_t>{3});  // 0.57 degrees from lock
    // the summary: the largest of the segments, and the gaps between keys
    REQUIRE(info.largest);
    // 180 about z to z 0.3 then y (pi/2 - 0.01): cos(angle/2) = their dot, sin(0.15) cos((pi/2 - 0.01) / 2)
    const double last = 2 * std::acos(std::sin(0.15) * std::cos((std::numbers::pi / 2 - 0.01) / 2)) * 180 / std::numbers::pi;
    CHECK(std::fabs(info.largest->angle_deg - last) <= 1e-9);
    CHECK(info.largest_from == 2);
    CHECK(std::fabs(info.segments[2].angle_deg - last) <= 1e-9);
    CHECK(info.shortest_gap == 0.5);
    CHECK(info.longest_gap == 1);
    CHECK(!info.even());
}
