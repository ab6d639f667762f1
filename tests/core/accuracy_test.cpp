// SPDX-License-Identifier: MIT
// Accuracy against the __float128 reference, decade by decade from 1e-100
// rad to pi, near the half turn and near gimbal lock.
#include <doctest/doctest.h>

#include "accuracy.hpp"
#include "helpers.hpp"

using namespace keyrot;
using namespace keyrot::accuracy;

TEST_CASE("every conversion and interpolation is within its bound in every decade") {
    for (const measurement& m : measurements()) {
        for (const band& b : bands()) {
            CAPTURE(m.name);
            CAPTURE(b.label);
            const double w = worst(m, b, 40, 1234);
            CAPTURE(w);
            CHECK(w <= m.bound);
        }
    }
}

TEST_CASE("the reference itself: exact cases") {
    // 90 degrees about z, written with the correctly rounded sqrt(1/2)
    const ref::q128 q = ref::from_axis_angle(0, 0, 1, ref::f128(std::numbers::pi) / 2);
    CHECK(std::fabs(ref::narrow(q.w) - std::sqrt(0.5)) <= 1e-16);
    CHECK(ref::narrow(ref::angle_of(q)) == std::numbers::pi / 2);
    CHECK(ref::narrow(ref::rotation_error(q, q)) == 0);
}

TEST_CASE("tiny and near-half-turn angles from the command line's point of view") {
    // 1e-100 rad in, the same angle out, to the last bit or one off
    const quat q = from_axis_angle({0, 0, 1}, 1e-100);
    CHECK(std::fabs(to_axis_angle(q).angle - 1e-100) <= 2.3e-116);
    // within 1e-12 of 180 degrees
    const double near_pi = std::numbers::pi - 1e-12;
    CHECK(std::fabs(to_axis_angle(from_axis_angle({1, 0, 0}, near_pi)).angle - near_pi) <= 4.5e-16);
    // a pure pitch of 1e-10 rad comes back to full relative precision
    const euler_seq zyx = *parse_euler_seq("ZYX");
    CHECK(std::fabs(to_euler(from_euler({0, 1e-10, 0}, zyx), zyx).angles[1] - 1e-10) <= 1e-25);
}
