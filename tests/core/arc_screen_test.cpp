// SPDX-License-Identifier: MIT
// arc_screen: its verdicts against the exact comparison reduce makes
// (slerp_segment's point, geodesic_angle in degrees, <= the tolerance).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <random>
#include <vector>

#include "core/arc_screen.hpp"
#include "keyrot/convert.hpp"
#include "keyrot/interpolate.hpp"

using namespace keyrot;

namespace {

/// `deg` degrees about the axis (x, y, z).
quat turn(double x, double y, double z, double deg) {
    const double n = std::sqrt(x * x + y * y + z * z), h = deg * M_PI / 360;
    return {std::cos(h), std::sin(h) * x / n, std::sin(h) * y / n, std::sin(h) * z / n};
}

double exact_deg(quat a, quat b, double h, quat k) {
    return from_radians(geodesic_angle(slerp(a, b, h), k), angle_unit::degrees);
}

}  // namespace

TEST_CASE("arc_screen: within and beyond only where the exact comparison agrees, unsure near the tolerance; its bound") {
    std::mt19937_64 rng(48);
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> uniform(0, 1);
    const auto random_turn = [&](double deg) { return turn(normal(rng), normal(rng), normal(rng), deg); };
    // Keys at these multiples of the tolerance from the arc's point.
    const double factors[] = {0, 0.5, 1 - 1e-6, 1 - 1e-12, 1 - 1e-15, 1, 1 + 1e-15, 1 + 1e-12, 1 + 1e-6, 2};
    std::size_t decided = 0, clear = 0, unsure_near = 0, near = 0;
    for (std::size_t trial = 0; trial < 20000; ++trial) {
        const double tol = std::vector<double>{1e-7, 1e-3, 0.01, 1, 30, 90}[trial % 6];
        const quat a = random_turn(360 * uniform(rng));
        // b up to 180 degrees of rotation on, in a's hemisphere, some nearly a
        const double apart = trial % 5 == 0 ? 1e-9 * uniform(rng) : 179.9 * uniform(rng);
        quat b = a * random_turn(apart);
        if (dot(a, b) <= 0) b = -b;
        const double h = uniform(rng);
        const double factor = factors[trial % std::size(factors)];
        const quat k = slerp(a, b, h) * random_turn(tol * factor);
        arc_screen screen(a, b, arc_screen::sin_half(tol));
        REQUIRE(screen.usable());
        const arc_screen::finding f = screen.at(h, k);
        const arc_screen::verdict v = f.v;
        const double deg = exact_deg(a, b, h, k);
        if (v == arc_screen::verdict::within) CHECK(deg <= tol);
        if (v == arc_screen::verdict::beyond) CHECK(deg > tol);
        // The bound on the exact angle holds, and where the key's distance
        // was measured (not found off the great circle: 1) it is close, a hair over.
        CHECK(deg <= arc_screen::most_deg(f.sin_off_sq));
        if (f.sin_off_sq < 1) CHECK(arc_screen::most_deg(f.sin_off_sq) <= deg * (1 + 1e-8) + 1e-10);
        if (v != arc_screen::verdict::beyond) CHECK(f.sin_off_sq < 1);
        // Keys clearly in or out are decided (the screen saves the exact curve there).
        if ((factor == 0.5 || factor == 2 || factor == 1 - 1e-6 || factor == 1 + 1e-6) && tol >= 1e-3) {
            ++clear;
            if (v != arc_screen::verdict::unsure) ++decided;
        }
        if (factor == 1 || factor == 1 - 1e-15 || factor == 1 + 1e-15) {
            ++near;
            if (v == arc_screen::verdict::unsure) ++unsure_near;
        }
    }
    CHECK(decided == clear);
    CHECK(unsure_near == near);  // a key at the tolerance is the exact comparison's to decide
}

TEST_CASE("arc_screen: keys off the arc's great circle, by a hair or plainly, with one screen for many keys as a probe uses it") {
    std::mt19937_64 rng(4848);
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> uniform(0, 1);
    const auto random_turn = [&](double deg) { return turn(normal(rng), normal(rng), normal(rng), deg); };
    const double factors[] = {0.5, 1 - 1e-6, 1 - 1e-12, 1, 1 + 1e-12, 1 + 1e-6, 2, 1000};
    std::size_t clear = 0, decided = 0, off_circle = 0;
    for (std::size_t trial = 0; trial < 4000; ++trial) {
        const double tol = std::vector<double>{1e-3, 0.01, 1, 30, 90}[trial % 5];
        const quat a = random_turn(360 * uniform(rng));
        const double apart = std::vector<double>{1e-9, 1e-4, 1, 90, 179.9}[trial / 5 % 5] * uniform(rng);
        quat b = a * random_turn(apart);
        if (dot(a, b) <= 0) b = -b;
        // n: a unit quaternion square to a and b, the way off their great circle.
        quat n{normal(rng), normal(rng), normal(rng), normal(rng)};
        const quat u = normalized(b + -dot(a, b) * a);
        n = normalized(n + -dot(n, a) * a + -dot(n, u) * u);
        arc_screen screen(a, b, arc_screen::sin_half(tol));
        REQUIRE(screen.usable());
        for (std::size_t i = 0; i < 6; ++i) {  // the first keys off the circle, the later ones near the arc's point
            const double h = uniform(rng);
            const double factor = factors[(trial + i) % std::size(factors)];
            const double off = std::min(M_PI / 2, tol * factor * M_PI / 360);
            const quat c = slerp(a, b, h);
            const quat k = i < 3 ? normalized(std::cos(off) * c + std::sin(off) * n) : c * random_turn(tol * factor);
            const arc_screen::finding f = screen.at(h, k);
            const double deg = exact_deg(a, b, h, k);
            if (f.v == arc_screen::verdict::within) CHECK(deg <= tol);
            if (f.v == arc_screen::verdict::beyond) CHECK(deg > tol);
            CHECK(deg <= arc_screen::most_deg(f.sin_off_sq));
            off_circle += f.v == arc_screen::verdict::beyond && f.sin_off_sq == 1;
            // Clearly in or out, on arcs long enough for their circle to be sure.
            if ((factor <= 1 - 1e-6 || factor >= 1 + 1e-6) && apart >= 1e-3) ++clear, decided += f.v != arc_screen::verdict::unsure;
        }
    }
    CHECK(decided == clear);
    CHECK(off_circle > 1000);  // keys found beyond the arc by its great circle alone, before its angle was needed
}

TEST_CASE("arc_screen: not used for keys more than 180 degrees apart, equal keys or a tolerance over 90 degrees") {
    const quat a = turn(0, 0, 1, 10);
    const double sin_tol = arc_screen::sin_half(0.01);
    CHECK(arc_screen(a, a * turn(1, 0, 0, 90), sin_tol).usable());
    CHECK_FALSE(arc_screen(a, -(a * turn(1, 0, 0, 90)), sin_tol).usable());  // the long way round
    CHECK_FALSE(arc_screen(a, a, sin_tol).usable());
    CHECK(std::isnan(arc_screen::sin_half(91)));
    CHECK(std::isnan(arc_screen::sin_half(-1)));
    CHECK_FALSE(arc_screen(a, a * turn(1, 0, 0, 90), arc_screen::sin_half(91)).usable());
    CHECK(arc_screen(a, a * turn(1, 0, 0, 90), arc_screen::sin_half(90)).usable());
    CHECK(arc_screen(a, a * turn(1, 0, 0, 90), arc_screen::sin_half(0)).usable());
    CHECK(arc_screen(a, a * turn(1, 0, 0, 90), sin_tol).at(0.5, a).v == arc_screen::verdict::beyond);
    CHECK(arc_screen(a, a * turn(1, 0, 0, 90), sin_tol).at(0.5, a * turn(1, 0, 0, 45)).v == arc_screen::verdict::within);
    // Off the great circle (about y, square to the arc's x): beyond by the circle alone.
    CHECK(arc_screen(a, a * turn(1, 0, 0, 90), sin_tol).at(0.5, a * turn(0, 1, 0, 1)).sin_off_sq == 1);
    // A tolerance of 0: only a key the exact comparison finds on the arc is within, so none is sure.
    CHECK(arc_screen(a, a * turn(1, 0, 0, 90), arc_screen::sin_half(0)).at(0.5, a * turn(1, 0, 0, 45)).v ==
          arc_screen::verdict::unsure);
    arc_screen opposite(a, -a, sin_tol);
    CHECK(opposite.at(0.5, a).v == arc_screen::verdict::unsure);
    CHECK(arc_screen::most_deg(opposite.at(0.5, a).sin_off_sq) >= 180);
}
