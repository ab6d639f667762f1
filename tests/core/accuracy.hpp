// SPDX-License-Identifier: MIT
#pragma once
// The accuracy sweep shared by accuracy_test.cpp (which asserts the bounds)
// and accuracy_report.cpp (which prints the table in the README): each
// measurement takes a rotation angle and returns one sample's error against
// the __float128 reference; bands sweep the angle decade by decade.
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "keyrot/convert.hpp"
#include "keyrot/interpolate.hpp"
#include "reference.hpp"

namespace keyrot::accuracy {

using ref::f128;
using ref::narrow;
using ref::widen;

/// Rotation angles theta = lo..hi, or pi - (lo..hi) near the half turn.
struct band {
    std::string label;
    double lo, hi;
    bool below_pi = false;
};

/// 1e-100 to pi decade by decade, then within 1e-13..1e-1 of pi, then pi.
inline std::vector<band> bands() {
    std::vector<band> out;
    for (int e = -100; e < 0; ++e) out.push_back({"1e" + std::to_string(e), std::pow(10.0, e), std::pow(10.0, e + 1)});
    out.push_back({"1..pi", 1, std::numbers::pi});
    for (int e = -13; e < 0; ++e)
        out.push_back({"pi-1e" + std::to_string(e), std::pow(10.0, e), std::pow(10.0, e + 1), true});
    out.push_back({"pi", 0, 0, true});
    return out;
}

class sampler {
public:
    explicit sampler(unsigned seed) : gen_(seed) {}
    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(gen_); }
    /// Log-uniform in [lo, hi), or pi - that for a band below pi.
    double angle(const band& b) {
        if (b.hi == 0) return std::numbers::pi;
        const double x = std::exp(uniform(std::log(b.lo), std::log(b.hi)));
        return b.below_pi ? std::numbers::pi - x : x;
    }
    vec3 axis() {
        std::normal_distribution<double> n;
        const vec3 v{n(gen_), n(gen_), n(gen_)};
        return (1 / norm(v)) * v;
    }
    quat rotation() { return from_axis_angle(axis(), uniform(0, std::numbers::pi)); }
    bool coin() { return uniform(0, 1) < 0.5; }
    euler_seq sequence() {
        static const char* names[] = {"XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX", "XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ",
                                      "xyz", "xzy", "yxz", "yzx", "zxy", "zyx", "xyx", "xzx", "yxy", "yzy", "zxz", "zyz"};
        return *parse_euler_seq(names[static_cast<int>(uniform(0, 24)) % 24]);
    }

private:
    std::mt19937_64 gen_;
};

struct measurement {
    std::string name;
    std::string unit;  ///< "rad" (rotation error) or "rel" (relative error of an angle)
    double bound;
    /// One sample's error for a rotation of angle theta (radians).
    std::function<double(double theta, sampler&)> error;
};

namespace detail {

inline double rel(double got, f128 want) { return want == 0 ? std::fabs(got) : narrow(fabsq((got - want) / want)); }

inline double rot(quat got, const ref::q128& want) { return narrow(ref::rotation_error(widen(got), want)); }

/// A rotation of angle theta about a random axis, as a double quaternion,
/// with w < 0 half of the time.
inline quat test_rotation(double theta, sampler& s) {
    const quat q = from_axis_angle(s.axis(), theta);
    return s.coin() ? -q : q;
}

inline double middle_lock(const euler_seq& seq, bool upper) {
    if (seq.axes[0] != seq.axes[2]) return upper ? std::numbers::pi / 2 : -std::numbers::pi / 2;
    return upper ? std::numbers::pi : 0;
}

}  // namespace detail

inline std::vector<measurement> measurements() {
    using namespace detail;
    std::vector<measurement> m;
    m.push_back({"quat->axis-angle: angle", "rel", 1e-15, [](double theta, sampler& s) {
                     const quat q = test_rotation(theta, s);
                     return rel(to_axis_angle(q).angle, ref::angle_of(widen(q)));
                 }});
    m.push_back({"quat->axis-angle: rotation", "rad", 4e-16, [](double theta, sampler& s) {
                     const quat q = test_rotation(theta, s);
                     const axis_angle aa = to_axis_angle(q);
                     return rot(q, ref::from_axis_angle(aa.axis.x, aa.axis.y, aa.axis.z, aa.angle));
                 }});
    m.push_back({"axis-angle->quat", "rad", 4e-16, [](double theta, sampler& s) {
                     const vec3 n = 3.0 * s.axis();  // not unit on purpose
                     return rot(from_axis_angle(n, theta), ref::from_axis_angle(n.x, n.y, n.z, theta));
                 }});
    m.push_back({"quat->rotvec: length", "rel", 1e-15, [](double theta, sampler& s) {
                     const quat q = test_rotation(theta, s);
                     const vec3 r = to_rotvec(q);
                     const f128 len = sqrtq(f128(r.x) * r.x + f128(r.y) * r.y + f128(r.z) * r.z);
                     return narrow(fabsq((len - ref::angle_of(widen(q))) / ref::angle_of(widen(q))));
                 }});
    m.push_back({"rotvec->quat", "rad", 4e-16, [](double theta, sampler& s) {
                     const vec3 r = theta * s.axis();
                     const f128 len = sqrtq(f128(r.x) * r.x + f128(r.y) * r.y + f128(r.z) * r.z);
                     return rot(from_rotvec(r), ref::from_axis_angle(r.x, r.y, r.z, len));
                 }});
    m.push_back({"quat->matrix: entries", "abs", 4e-16, [](double theta, sampler& s) {
                     const quat q = test_rotation(theta, s);
                     const mat3 got = to_matrix(q);
                     const auto want = ref::to_matrix(widen(q));
                     double worst = 0;
                     for (std::size_t r = 0; r < 3; ++r)
                         for (std::size_t c = 0; c < 3; ++c)
                             worst = std::fmax(worst, narrow(fabsq(got.m[r][c] - want[r][c])));
                     return worst;
                 }});
    m.push_back({"matrix->quat", "rad", 4e-16, [](double theta, sampler& s) {
                     const mat3 mat = to_matrix(test_rotation(theta, s));
                     return rot(from_matrix(mat), ref::from_matrix(mat));
                 }});
    // Three angles in [-pi, pi], each correctly rounded, already move the
    // rotation by up to 3 x 2.2e-16: twice that is the bound for Euler output.
    m.push_back({"quat->euler (24 seqs): rotation", "rad", 1.3e-15, [](double theta, sampler& s) {
                     const quat q = test_rotation(theta, s);
                     const euler_seq seq = s.sequence();
                     const auto e = to_euler(q, seq).angles;
                     return narrow(ref::rotation_error(ref::from_euler({e[0], e[1], e[2]}, seq), widen(q)));
                 }});
    m.push_back({"euler->quat (24 seqs)", "rad", 4e-16, [](double theta, sampler& s) {
                     const euler_seq seq = s.sequence();
                     const std::array<double, 3> e = {theta * s.uniform(-1, 1), theta * s.uniform(-1, 1),
                                                      theta * s.uniform(-1, 1)};
                     return rot(from_euler(e, seq), ref::from_euler({e[0], e[1], e[2]}, seq));
                 }});
    m.push_back({"quat->euler: middle angle, one axis", "rel", 1e-15, [](double theta, sampler& s) {
                     // A rotation about the sequence's middle axis only: the
                     // middle angle is the rotation angle, to full precision.
                     const euler_seq seq = s.sequence();
                     const bool proper = seq.axes[0] == seq.axes[2];
                     const double angle = proper ? theta : std::fmin(theta, std::numbers::pi / 2);
                     std::array<double, 3> e{0, angle, 0};
                     const quat q = from_euler(e, seq);
                     return rel(to_euler(q, seq).angles[1], ref::angle_of(widen(q)));
                 }});
    m.push_back({"quat->euler: near gimbal lock", "rad", 1.3e-15, [](double theta, sampler& s) {
                     // theta is the middle angle's distance from its lock value.
                     const euler_seq seq = s.sequence();
                     const bool upper = s.coin();
                     const f128 lock = middle_lock(seq, upper);
                     const f128 middle = upper ? lock - std::fmin(theta, 1.0) : lock + std::fmin(theta, 1.0);
                     const ref::q128 exact = ref::from_euler({s.uniform(-3, 3), middle, s.uniform(-3, 3)}, seq);
                     const quat q{narrow(exact.w), narrow(exact.x), narrow(exact.y), narrow(exact.z)};
                     const auto e = to_euler(q, seq).angles;
                     return narrow(ref::rotation_error(ref::from_euler({e[0], e[1], e[2]}, seq), widen(q)));
                 }});
    m.push_back({"slerp (incl. long way)", "rad", 4e-16, [](double theta, sampler& s) {
                     const quat a = s.rotation();
                     quat b = a * from_axis_angle(s.axis(), theta);
                     if (s.coin()) b = -b;  // the long way round, as --path direct takes it
                     const double h = s.uniform(0, 1);
                     return rot(slerp(a, b, h), ref::slerp(widen(a), widen(b), h));
                 }});
    m.push_back({"nlerp", "rad", 4e-16, [](double theta, sampler& s) {
                     const quat a = s.rotation();
                     const quat b = a * from_axis_angle(s.axis(), theta);
                     const double h = s.uniform(0, 1);
                     return rot(nlerp(a, b, h), ref::nlerp(widen(a), widen(b), h));
                 }});
    m.push_back({"squad", "rad", 4e-16, [](double theta, sampler& s) {
                     std::array<quat, 4> q{s.rotation()};
                     for (std::size_t i = 1; i < 4; ++i) q[i] = q[i - 1] * from_axis_angle(s.axis(), theta * s.uniform(0.5, 1));
                     const double h = s.uniform(0, 1);
                     // The curve resample evaluates: keys 0..3 one second apart, signs as given.
                     track t;
                     for (std::size_t i = 0; i < 4; ++i) {
                         t.keys.emplace_back();
                         t.keys.back().time = static_cast<double>(i);
                         t.keys.back().rotation = q[i];
                     }
                     const rotation_curve curve(t, method::squad, path::direct);
                     const ref::q128 r1 = ref::squad_control(widen(q[0]), widen(q[1]), widen(q[2]));
                     const ref::q128 r2 = ref::squad_control(widen(q[1]), widen(q[2]), widen(q[3]));
                     const ref::q128 want = ref::slerp(ref::slerp(widen(q[1]), widen(q[2]), h), ref::slerp(r1, r2, h), 2 * h * (1 - h));
                     return rot(curve.at(1, h), want);
                 }});
    return m;
}

/// The largest error of `samples` draws in one band.
inline double worst(const measurement& m, const band& b, int samples, unsigned seed) {
    sampler s(seed);
    double w = 0;
    for (int i = 0; i < samples; ++i) w = std::fmax(w, m.error(s.angle(b), s));
    return w;
}

}  // namespace keyrot::accuracy
