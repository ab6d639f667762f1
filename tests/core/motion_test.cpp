// SPDX-License-Identifier: MIT
#include "keyrot/motion.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "helpers.hpp"
#include "keyrot/convert.hpp"
#include "keyrot/interpolate.hpp"
#include "keyrot/rotation_spline.hpp"

using namespace keyrot;
using keyrot::test::same_rotation;

namespace {

double max_abs(const mat3& m) {
    double worst = 0;
    for (const auto& row : m.m)
        for (double x : row) worst = std::fmax(worst, std::fabs(x));
    return worst;
}

double distance(vec3 a, vec3 b) { return norm(a - b); }

/// exp of the pure quaternion phi/2: the rotation of rotation vector phi.
quat turn(vec3 phi) { return exp(0.5 * phi); }

key at(double time, quat q) { return test::key_at(time, q); }

}  // namespace

TEST_CASE("the rate matrices are inverse to each other, on both sides of the series' bound") {
    for (double angle : {0.0, 1e-8, 1e-3, 0.3, 0.999999, 1.0, 1.000001, 2.0, 3.0, 3.1}) {
        const vec3 phi = angle * vec3{0.48, -0.6, 0.64};
        const mat3 product = rate_matrix(phi) * inverse_rate_matrix(phi);
        const mat3 off = product + (-1.0) * mat3{{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}};
        CHECK(max_abs(off) < 1e-14);
    }
}

TEST_CASE("the series and the closed forms meet at the bound") {
    // Either side of 1 radian, the coefficients of each form differ by the step alone.
    const vec3 axis{0.6, 0, 0.8}, other{0.1, 0.9, -0.3};
    const double below = 1 - 1e-9, above = 1 + 1e-9;
    CHECK(max_abs(rate_matrix(below * axis) + (-1.0) * rate_matrix(above * axis)) < 1e-8);
    CHECK(max_abs(inverse_rate_matrix(below * axis) + (-1.0) * inverse_rate_matrix(above * axis)) < 1e-8);
    CHECK(distance(rate_curvature(below * axis, other), rate_curvature(above * axis, other)) < 1e-8);
}

TEST_CASE("rate_matrix is the derivative of exp: a finite difference of key exp(phi)") {
    const quat key_q = from_axis_angle({0, 0, 1}, 30, angle_unit::degrees);
    const vec3 phi{0.7, -0.4, 1.1}, phi_dot{0.3, 0.5, -0.2};
    const double h = 1e-6;
    const quat before = key_q * turn(phi - h * phi_dot), after = key_q * turn(phi + h * phi_dot);
    const vec3 fd = (1 / (2 * h)) * (2.0 * log(conjugate(before) * after));
    CHECK(distance(fd, rate_matrix(phi) * phi_dot) < 1e-8);
    // and the curvature term the derivative of the velocity along a straight path phi + t phi_dot
    const vec3 w_before = rate_matrix(phi - h * phi_dot) * phi_dot, w_after = rate_matrix(phi + h * phi_dot) * phi_dot;
    CHECK(distance((1 / (2 * h)) * (w_after - w_before), rate_curvature(phi, phi_dot)) < 1e-8);
}

TEST_CASE("a steady turn: velocity w, no acceleration, in either frame") {
    const vec3 w{0.2, -1.5, 0.7};
    const quat start = from_axis_angle({1, 0, 0}, 40, angle_unit::degrees);
    // q(t) = start exp(t w / 2) at t = 0.3: q' = q (0, w/2), q'' = q (0, w/2)^2
    const quat q = start * turn(0.3 * w);
    const quat half{0, w.x / 2, w.y / 2, w.z / 2};
    const motion m = motion_of(quat_jet{q, q * half, q * half * half});
    CHECK(distance(m.velocity, w) < 1e-15);
    CHECK(norm(m.acceleration) < 1e-15);
    const motion fixed = in_fixed_frame(q, m);
    CHECK(distance(fixed.velocity, rotate(q, w)) < 1e-15);
    CHECK(motion_of(vec3{}, w, vec3{}).velocity.x == w.x);
}

TEST_CASE("spline_key_rates: a steady turn about one axis is that rate at every key") {
    // Uneven keys on one axis at 2 rad/s: the spline is the steady turn itself.
    const std::vector<double> times{0, 0.1, 0.35, 0.4, 1.0};
    std::vector<quat> keys;
    for (double t : times) keys.push_back(turn((2 * t) * vec3{0, 0.6, 0.8}));
    const spline_rates r = spline_key_rates(times, keys);
    CHECK(r.status.converged);
    for (const vec3& w : r.velocity) CHECK(distance(w, {0, 1.2, 1.6}) < 1e-13);
}

TEST_CASE("spline_key_rates: two keys move at the mean rate (slerp)") {
    const std::vector<double> times{1, 3};
    const std::vector<quat> keys{quat{}, from_axis_angle({0, 0, 1}, 90, angle_unit::degrees)};
    const spline_rates r = spline_key_rates(times, keys);
    REQUIRE(r.velocity.size() == 2);
    CHECK(distance(r.velocity[0], {0, 0, std::numbers::pi / 4}) < 1e-15);
    CHECK(distance(r.velocity[1], {0, 0, std::numbers::pi / 4}) < 1e-15);
}

TEST_CASE("cubic passes through its keys and meets the next segment with the same velocity and acceleration") {
    segment_builder builder(method::cubic, path::shortest, std::nullopt);
    const double times[] = {0, 0.4, 0.5, 1.3};
    const quat keys[] = {quat{}, from_axis_angle({1, 0, 0}, 50, angle_unit::degrees),
                         from_axis_angle({0.6, 0.8, 0}, 80, angle_unit::degrees),
                         -from_axis_angle({0, 0, 1}, 170, angle_unit::degrees)};  // (signed the long way: flipped)
    for (int i = 0; i < 4; ++i) builder.add(at(times[i], keys[i]));
    segment s;
    CHECK_FALSE(builder.pop(s, false));  // none before the end
    std::vector<segment_curve> curves;
    while (builder.pop(s, true)) curves.push_back(s.curve());
    REQUIRE(curves.size() == 3);
    for (std::size_t i = 0; i < 3; ++i) {
        CHECK(same_rotation(curves[i].at(0), keys[i], 0));
        CHECK(same_rotation(curves[i].at(1), keys[i + 1], 1e-14));
    }
    for (std::size_t i = 0; i + 1 < 3; ++i) {
        const motion end = curves[i].rates(1), start = curves[i + 1].rates(0);
        CHECK(distance(end.velocity, start.velocity) < 1e-12 * (1 + norm(start.velocity)));
        CHECK(distance(end.acceleration, start.acceleration) < 1e-10 * (1 + norm(start.acceleration)));
    }
}

TEST_CASE("every method's rates: slerp steady, step still") {
    const quat a{}, b = from_axis_angle({0, 0, 1}, 90, angle_unit::degrees);
    for (method m : {method::slerp, method::step}) {
        segment_builder builder(m, path::shortest, std::nullopt);
        builder.add(at(0, a)), builder.add(at(2, b));
        segment s;
        REQUIRE(builder.pop(s, true));
        const motion r = s.curve().rates(0.3);
        CHECK(distance(r.velocity, m == method::slerp ? vec3{0, 0, std::numbers::pi / 4} : vec3{}) < 1e-15);
        CHECK(norm(r.acceleration) == 0);
    }
}

TEST_CASE("curvature_jacobian is the derivative of rate_curvature in its second argument") {
    for (double angle : {0.2, 1.5, 3.0}) {
        const vec3 phi = angle * vec3{0.36, 0.48, 0.8}, v{0.7, -1.2, 0.4};
        const curvature_coefficients k = curvature_of(phi);
        const mat3 j = curvature_jacobian(phi, v, k);
        const double h = 1e-6;
        for (std::size_t c = 0; c < 3; ++c) {
            vec3 e;
            (c == 0 ? e.x : c == 1 ? e.y : e.z) = h;
            const vec3 fd = (1 / (2 * h)) * (rate_curvature(phi, v + e, k) - rate_curvature(phi, v - e, k));
            const vec3 column{j.m[0][c], j.m[1][c], j.m[2][c]};
            CHECK(distance(fd, column) < 1e-8);
        }
    }
}

TEST_CASE("cubic solved a stretch at a time is the spline solved whole, to rounding") {
    // Tracks of three stretches, steps of up to 10, 90 and 150
    // degrees, keys 10 ms to 0.5 s apart: the stretches' look-ahead leaves
    // an effect far below 1e-12 degrees.
    for (double step : {10.0, 90.0, 150.0}) {
        std::vector<double> times;
        std::vector<quat> keys;
        double time = 0;
        quat q{};
        keyrot::test::random_rotations axes(static_cast<unsigned>(step));
        for (std::size_t i = 0; i < 3 * cubic_stretch; ++i) {
            const vec3 axis = vector_part(axes.next());
            time += axes.uniform(0.01, 0.5);
            q = q * from_axis_angle((1 / norm(axis)) * axis, step * axes.uniform(0.3, 1), angle_unit::degrees);
            if (!keys.empty() && dot(keys.back(), q) < 0) q = -q;
            times.push_back(time), keys.push_back(q);
        }
        const spline_rates whole = spline_key_rates(times, keys);
        REQUIRE(whole.status.converged);
        segment_builder builder(method::cubic, path::shortest, std::nullopt);
        double worst = 0;
        std::size_t i = 0;
        segment s;
        const auto compare = [&] {
            const segment_curve c = s.curve();
            const spline_segment ref(keys[i], rotation_vector_between(keys[i], keys[i + 1]), times[i + 1] - times[i],
                                     whole.velocity[i], whole.velocity[i + 1]);
            for (double h : {0.3, 0.7}) worst = std::fmax(worst, geodesic_angle(c.at(h), ref.at(h)));
            ++i;
        };
        for (std::size_t k = 0; k < keys.size(); ++k) {
            builder.add(at(times[k], keys[k]));
            while (builder.pop(s, false)) compare();
        }
        while (builder.pop(s, true)) compare();
        CHECK(i == keys.size() - 1);
        CHECK(worst * 180 / std::numbers::pi < 1.5e-12);
        MESSAGE("steps to ", step, " deg: ", worst * 180 / std::numbers::pi, " deg from the spline solved whole");
    }
}
