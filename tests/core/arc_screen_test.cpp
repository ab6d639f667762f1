// arc_screen: its verdicts against the exact comparison reduce makes
// (slerp_segment's point, geodesic_angle in degrees, <= the tolerance).
#include <doctest/doctest.h>

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
        const arc_screen screen(a, b, tol);
        REQUIRE(screen.usable());
        const arc_screen::finding f = screen.at(h, k);
        const arc_screen::verdict v = f.v;
        const double deg = exact_deg(a, b, h, k);
        if (v == arc_screen::verdict::within) CHECK(deg <= tol);
        if (v == arc_screen::verdict::beyond) CHECK(deg > tol);
        // The bound on the exact angle holds, and is close: a hair over it.
        CHECK(deg <= screen.most_deg(f.sin_off));
        CHECK(screen.most_deg(f.sin_off) <= deg * (1 + 1e-8) + 1e-10);
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

TEST_CASE("arc_screen: not used for keys more than 180 degrees apart, equal keys or a tolerance over 90 degrees") {
    const quat a = turn(0, 0, 1, 10);
    CHECK(arc_screen(a, a * turn(1, 0, 0, 90), 0.01).usable());
    CHECK_FALSE(arc_screen(a, -(a * turn(1, 0, 0, 90)), 0.01).usable());  // the long way round
    CHECK_FALSE(arc_screen(a, a, 0.01).usable());
    CHECK_FALSE(arc_screen(a, a * turn(1, 0, 0, 90), 91).usable());
    CHECK(arc_screen(a, a * turn(1, 0, 0, 90), 0).usable());
    CHECK(arc_screen(a, a * turn(1, 0, 0, 90), 0.01).at(0.5, a).v == arc_screen::verdict::beyond);
    CHECK(arc_screen(a, a * turn(1, 0, 0, 90), 0.01).at(0.5, a * turn(1, 0, 0, 45)).v == arc_screen::verdict::within);
    CHECK(arc_screen(a, -a, 0.01).at(0.5, a).v == arc_screen::verdict::unsure);
    CHECK(arc_screen(a, -a, 0.01).most_deg(arc_screen(a, -a, 0.01).at(0.5, a).sin_off) >= 180);
}
