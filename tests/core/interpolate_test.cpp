// SPDX-License-Identifier: MIT
#include "keyrot/interpolate.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "helpers.hpp"

using namespace keyrot;
using keyrot::test::max_diff;
using keyrot::test::near;
using keyrot::test::same_rotation;

namespace {

constexpr double pi = std::numbers::pi;

/// Shoemake's sine form (Szeliski, eq. 2.45).
quat slerp_sine(quat a, quat b, double t) {
    const double omega = std::acos(std::fmax(-1.0, std::fmin(1.0, dot(a, b))));
    const double p = std::sin((1 - t) * omega) / std::sin(omega), q = std::sin(t * omega) / std::sin(omega);
    return {p * a.w + q * b.w, p * a.x + q * b.x, p * a.y + q * b.y, p * a.z + q * b.z};
}

/// The power form (q r^-1)^alpha r, the power written out as a turn:
/// r^alpha = (cos(alpha theta/2), sin(alpha theta/2) k).
quat slerp_power(quat r, quat q, double alpha) {
    const quat d = q * conjugate(r);
    const double half = std::acos(std::fmax(-1.0, std::fmin(1.0, d.w)));
    const double s = std::sin(half);
    const quat p{std::cos(alpha * half), std::sin(alpha * half) * d.x / s, std::sin(alpha * half) * d.y / s,
                 std::sin(alpha * half) * d.z / s};
    return p * r;
}

key make_key(double time, quat q) { return test::key_at(time, q); }

track make_track_of(const std::vector<quat>& qs, double spacing = 1) {
    track t;
    for (std::size_t i = 0; i < qs.size(); ++i) t.keys.push_back(make_key(static_cast<double>(i) * spacing, qs[i]));
    return t;
}

}  // namespace

TEST_CASE("method and path names") {
    for (const auto& [value, name] : names_of<method>) CHECK(parse<method>(name) == value);
    for (const auto& [value, name] : names_of<path>) CHECK(to_string(value) == name);
    CHECK(parse<method>("squad") == method::squad);
    CHECK(to_string(path::direct) == "direct");
    CHECK_FALSE(parse<method>("linear"));
    CHECK_FALSE(parse<path>("long"));
}

TEST_CASE("textbook example: halfway from identity to 90 degrees about z") {
    const double s = std::sqrt(2.0) / 2;
    const quat q = slerp(quat{1, 0, 0, 0}, quat{s, 0, 0, s}, 0.5);
    // [0 0 0.3827 0.9239] as (x, y, z, w) to four places; exactly sin and cos of 22.5 degrees
    CHECK(near(q.z, 0.3827, 5e-5));
    CHECK(near(q.w, 0.9239, 5e-5));
    CHECK(near(q.z, std::sin(pi / 8), 2e-16));
    CHECK(near(q.w, std::cos(pi / 8), 2e-16));
    CHECK(q.x == 0);
    CHECK(q.y == 0);
}

TEST_CASE("three formulations of slerp agree: atan2, sine and power forms") {
    keyrot::test::random_rotations rng(4);
    for (int n = 0; n < 300; ++n) {
        quat a = rng.next(), b = rng.next();
        if (dot(a, b) < 0) b = -b;  // the sine and power forms take the short way only then
        const double t = rng.uniform(0, 1);
        CAPTURE(n);
        const quat ours = slerp(a, b, t);  // Szeliski's atan2 form (Algorithm 2.1)
        CHECK(max_diff(ours, slerp_sine(a, b, t)) <= 1e-14);
        CHECK(max_diff(ours, slerp_power(a, b, t)) <= 1e-14);
    }
}

TEST_CASE("slerp: exact endpoints, q with itself, left-invariance") {
    keyrot::test::random_rotations rng(5);
    const quat a = rng.next(), b = rng.next(), p = rng.next();
    CHECK(max_diff(slerp(a, b, 0), a) == 0);
    CHECK(max_diff(slerp(a, b, 1), b) == 0);
    CHECK(max_diff(slerp(a, a, 0.3), a) <= 2e-16);
    for (double t : {0.1, 0.5, 0.9}) CHECK(max_diff(slerp(p * a, p * b, t), p * slerp(a, b, t)) <= 1e-15);
}

TEST_CASE("slerp has constant angular speed; nlerp does not") {
    // 120 degrees about an oblique axis
    const quat a{}, bb = exp((pi / 3) * vec3{0.6, 0, 0.8});
    const double total = geodesic_angle(a, bb);
    CHECK(near(total, 2 * pi / 3, 1e-15));
    // The lerp of two unit 4-vectors theta = 60 degrees apart makes the angle
    // atan2(t sin theta, 1 - t + t cos theta) with the first; the rotation turns twice that.
    const double theta = pi / 3;
    double worst_slerp = 0, worst_nlerp = 0;
    for (int i = 1; i < 10; ++i) {
        const double t = i / 10.0;
        CAPTURE(t);
        worst_slerp = std::fmax(worst_slerp, std::fabs(geodesic_angle(a, slerp(a, bb, t)) - t * total));
        const double nlerp_angle = geodesic_angle(a, nlerp(a, bb, t));
        CHECK(near(nlerp_angle, 2 * std::atan2(t * std::sin(theta), 1 - t + t * std::cos(theta)), 1e-15));
        worst_nlerp = std::fmax(worst_nlerp, std::fabs(nlerp_angle - t * total));
    }
    CHECK(worst_slerp <= 1e-15);
    CHECK(worst_nlerp > 0.03);  // 2.2 degrees behind at t = 0.2
    // but nlerp follows the same great arc and keeps the endpoints
    CHECK(max_diff(nlerp(a, bb, 0), a) == 0);
    CHECK(max_diff(nlerp(a, bb, 1), bb) == 0);
    CHECK(max_diff(nlerp(a, bb, 0.5), slerp(a, bb, 0.5)) <= 1e-15);
}

TEST_CASE("slerp turns the long way when the signs say so, and a full turn for b = -a") {
    const double s = std::sqrt(0.5);
    const quat a{}, b{-s, 0, 0, -s};  // 90 about z, written with w < 0: 270 the long way
    const quat mid = slerp(a, b, 0.5);
    CHECK(near(geodesic_angle(a, mid), 3 * pi / 4, 1e-15));  // half of 270
    const quat full = slerp(a, -a, 0.5);
    CHECK(near(geodesic_angle(a, full), pi, 1e-15));
    CHECK(same_rotation(slerp(a, -a, 0.5), quat{0, 1, 0, 0}, 1e-16));
    CHECK(same_rotation(nlerp(a, -a, 0.5), a, 0));
}

TEST_CASE("keys exactly 180 degrees apart: slerp turns about the axis as written") {
    const quat a{}, b{0, 0, 0, 1};  // 180 about +z; dot = 0
    const quat mid = slerp(a, b, 0.5);
    CHECK(mid.z > 0);
    CHECK(near(mid.w, std::sqrt(0.5), 1e-16));
    CHECK(slerp(a, -b, 0.5).z < 0);
}

TEST_CASE("squad passes through its keys and has continuous angular velocity") {
    const std::vector<quat> qs = {quat{}, exp(vec3{0.3, 0.1, 0}), exp(vec3{0.2, 0.6, -0.1}), exp(vec3{-0.1, 0.4, 0.5}),
                                  exp(vec3{0.1, 0.1, 0.2})};
    const track t = make_track_of(qs);
    const rotation_curve squad_curve(t, method::squad, path::shortest);
    const rotation_curve slerp_curve(t, method::slerp, path::shortest);
    for (std::size_t i = 0; i + 1 < qs.size(); ++i) {
        CHECK(max_diff(squad_curve.at(i, 0), qs[i]) == 0);  // the keys themselves, to the bit
        CHECK(max_diff(squad_curve.at(i, 1), qs[i + 1]) == 0);
    }
    // Angular velocity (body frame) on either side of each interior key.
    const double eps = 1e-5;
    auto velocity = [&](const rotation_curve& c, std::size_t seg, double h0, double h1) {
        return (1 / ((h1 - h0))) * (2.0 * log(conjugate(c.at(seg, h0)) * c.at(seg, h1)));
    };
    double squad_jump = 0, slerp_jump = 0;
    for (std::size_t i = 1; i + 1 < qs.size(); ++i) {
        const vec3 before = velocity(squad_curve, i - 1, 1 - eps, 1), after = velocity(squad_curve, i, 0, eps);
        squad_jump = std::fmax(squad_jump, norm(before - after));
        const vec3 sb = velocity(slerp_curve, i - 1, 1 - eps, 1), sa = velocity(slerp_curve, i, 0, eps);
        slerp_jump = std::fmax(slerp_jump, norm(sb - sa));
    }
    CHECK(squad_jump < 1e-4);  // O(eps): continuous
    CHECK(slerp_jump > 0.1);   // the test can see a jump: slerp has one
}

TEST_CASE("squad control points follow the spec's formula") {
    const quat a = exp(vec3{0.1, 0, 0}), b = exp(vec3{0, 0.2, 0}), c = exp(vec3{0, 0, 0.3});
    // s_i = q_i exp(-(log(q_i^-1 q_{i+1}) + log(q_i^-1 q_{i-1})) / 4), written out
    const vec3 l1 = log(conjugate(b) * c), l2 = log(conjugate(b) * a);
    const quat expected = b * exp(-0.25 * (l1 + l2));
    CHECK(max_diff(squad_control(a, b, c), expected) == 0);
    // collinear keys on one great circle: s_i = q_i, and squad = slerp
    const vec3 axis{0, 0.6, 0.8};
    const quat p = exp(0.1 * axis), q = exp(0.3 * axis), r = exp(0.5 * axis);
    CHECK(max_diff(squad_control(p, q, r), q) <= 1e-15);
}

TEST_CASE("step holds the key; euler interpolates the angles linearly") {
    const euler_seq zyx = *parse_euler_seq("ZYX");
    track t = make_track_of({quat{}, from_euler({-170 * pi / 180, 0, 0}, zyx)});
    t.euler = zyx;
    const rotation_curve step(t, method::step, path::shortest);
    CHECK(max_diff(step.at(0, 0.99), quat{}) == 0);
    // the classic "-170 versus 160" contrast: keys as Euler angles -170 and 160 about z
    track e;
    e.euler = zyx;
    for (double deg : {-170.0, 160.0}) {
        key k = make_key(static_cast<double>(e.keys.size()), from_euler({deg * pi / 180, 0, 0}, zyx));
        k.given_as = rep::euler;
        k.given = given_rotation{{deg, 0, 0, 0}, angle_unit::degrees};
        e.keys.push_back(k);
    }
    const rotation_curve euler_curve(e, method::euler, path::shortest);
    const rotation_curve slerp_curve(e, method::slerp, path::shortest);
    // halfway: Euler goes through -5 degrees (the long way), slerp through 175 (30 the short way)
    CHECK(same_rotation(euler_curve.at(0, 0.5), from_axis_angle({0, 0, 1}, -5 * pi / 180), 1e-15));
    CHECK(same_rotation(slerp_curve.at(0, 0.5), from_axis_angle({0, 0, 1}, 175 * pi / 180), 1e-15));
    track no_seq = make_track_of({quat{}, quat{}});
    try {
        rotation_curve(no_seq, method::euler, path::shortest);
        FAIL("method::euler without a sequence was played");
    } catch (const option_error& caught) {
        CHECK(caught.which == option::euler_sequence);
        CHECK(std::string(caught.what()) == "method euler needs an Euler sequence");  // no flag: the CLI words it
    }
}

TEST_CASE("path shortest flips keys into one hemisphere; direct keeps signs") {
    const double s = std::sqrt(0.5);
    const track t = make_track_of({quat{}, quat{-s, 0, 0, -s}});
    CHECK(rotation_curve(t, method::slerp, path::shortest).at_key(1).w > 0);
    CHECK(rotation_curve(t, method::slerp, path::direct).at_key(1).w < 0);
    CHECK(near(geodesic_angle(quat{}, rotation_curve(t, method::slerp, path::shortest).at(0, 0.5)), pi / 4, 1e-15));
    CHECK(near(geodesic_angle(quat{}, rotation_curve(t, method::slerp, path::direct).at(0, 0.5)), 3 * pi / 4, 1e-15));
}
