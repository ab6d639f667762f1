// SPDX-License-Identifier: MIT
// Slerp between two rotations with keyrot's library: the identity and a
// quarter turn about z (the textbook example: halfway is 45 degrees), in five steps, printed
// as axis-angle in degrees.
#include <cstdio>
#include <keyrot/convert.hpp>
#include <keyrot/interpolate.hpp>
#include <numbers>

int main() {
    const keyrot::quat from{};  // the identity
    const keyrot::quat to = keyrot::from_axis_angle({0, 0, 1}, 90, keyrot::angle_unit::degrees);
    for (int step = 0; step <= 4; ++step) {
        const double h = step / 4.0;
        const keyrot::axis_angle r = keyrot::to_axis_angle(keyrot::slerp(from, to, h));
        std::printf("h=%.2f axis=(%g, %g, %g) angle=%.10g deg\n", h, r.axis.x, r.axis.y, r.axis.z,
                    r.angle * 180 / std::numbers::pi);
    }
}
