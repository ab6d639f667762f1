// SPDX-License-Identifier: MIT
#pragma once
// A __float128 reference (113-bit significand, about 34 digits) for the
// accuracy suite: the same conversions written out plainly in quad
// precision and evaluated on the very doubles keyrot is given, so keyrot's
// double results can be held against nearly exact values.
#include <quadmath.h>

#include <array>

#include "keyrot/convert.hpp"
#include "keyrot/quat.hpp"
#include "keyrot/tolerances.hpp"

namespace keyrot::ref {

using f128 = __float128;

struct q128 {
    f128 w = 1, x = 0, y = 0, z = 0;
};

inline q128 widen(quat q) { return {q.w, q.x, q.y, q.z}; }
inline double narrow(f128 v) { return static_cast<double>(v); }

inline q128 mul(const q128& a, const q128& b) {
    return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
            a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}
inline q128 conj(const q128& q) { return {q.w, -q.x, -q.y, -q.z}; }
inline f128 vnorm(const q128& q) { return sqrtq(q.x * q.x + q.y * q.y + q.z * q.z); }
inline q128 unit(const q128& q) {
    const f128 n = sqrtq(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    return {q.w / n, q.x / n, q.y / n, q.z / n};
}

/// Angle in radians of the rotation between a and b, sign-invariant.
inline f128 rotation_error(const q128& a, const q128& b) {
    const q128 r = mul(conj(unit(a)), unit(b));
    return 2 * atan2q(vnorm(r), fabsq(r.w));
}

inline q128 from_axis_angle(f128 ax, f128 ay, f128 az, f128 angle) {
    const f128 n = sqrtq(ax * ax + ay * ay + az * az);
    const f128 s = sinq(angle / 2) / n;
    return {cosq(angle / 2), s * ax, s * ay, s * az};
}

/// Rotation angle in [0, pi] of the (normalised) quaternion.
inline f128 angle_of(const q128& q) { return 2 * atan2q(vnorm(q), fabsq(q.w)); }

inline std::array<std::array<f128, 3>, 3> to_matrix(const q128& u) {
    const q128 q = unit(u);
    const f128 w = q.w, x = q.x, y = q.y, z = q.z;
    return {{{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
             {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
             {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}}};
}

/// Shepperd's method on the given (double) matrix, in quad.
inline q128 from_matrix(const mat3& mat) {
    std::array<std::array<f128, 3>, 3> m;
    for (std::size_t r = 0; r < 3; ++r)
        for (std::size_t c = 0; c < 3; ++c) m[r][c] = mat.m[r][c];
    const f128 trace = m[0][0] + m[1][1] + m[2][2];
    if (trace >= m[0][0] && trace >= m[1][1] && trace >= m[2][2])
        return unit({1 + trace, m[2][1] - m[1][2], m[0][2] - m[2][0], m[1][0] - m[0][1]});
    std::size_t i = 0;
    if (m[1][1] > m[i][i]) i = 1;
    if (m[2][2] > m[i][i]) i = 2;
    const std::size_t j = (i + 1) % 3, k = (j + 1) % 3;
    std::array<f128, 3> v{};
    v[i] = 1 - trace + 2 * m[i][i];
    v[j] = m[j][i] + m[i][j];
    v[k] = m[k][i] + m[i][k];
    return unit({m[k][j] - m[j][k], v[0], v[1], v[2]});
}

inline q128 elementary(int axis, f128 angle) {
    q128 q{cosq(angle / 2), 0, 0, 0};
    (axis == 0 ? q.x : axis == 1 ? q.y : q.z) = sinq(angle / 2);
    return q;
}

inline q128 from_euler(const std::array<f128, 3>& e, const euler_seq& seq) {
    const q128 a = elementary(seq.axes[0], e[0]), b = elementary(seq.axes[1], e[1]), c = elementary(seq.axes[2], e[2]);
    return seq.intrinsic ? mul(mul(a, b), c) : mul(mul(c, b), a);
}

/// a (a^-1 b)^h: Szeliski's form of slerp, no sign flip; keys opposite to
/// within keyrot's tol::opposite_keys make a full turn about a's x axis, as
/// keyrot documents.
inline q128 slerp(const q128& a, const q128& b, f128 h) {
    const q128 r = mul(conj(a), b);
    const f128 s = vnorm(r);
    const f128 pi = 4 * atan2q(1, 1);
    if (r.w < 0 && s <= tol::opposite_keys) return mul(a, q128{cosq(h * pi), sinq(h * pi), 0, 0});
    if (s == 0) return a;
    const f128 half = atan2q(s, r.w);
    const f128 k = sinq(h * half) / s;
    return mul(a, q128{cosq(h * half), k * r.x, k * r.y, k * r.z});
}

inline q128 nlerp(const q128& a, const q128& b, f128 h) {
    return unit({(1 - h) * a.w + h * b.w, (1 - h) * a.x + h * b.x, (1 - h) * a.y + h * b.y, (1 - h) * a.z + h * b.z});
}

inline std::array<f128, 3> log(const q128& q) {
    const f128 s = vnorm(q);
    if (s == 0) return {0, 0, 0};
    const f128 k = atan2q(s, q.w) / s;
    return {k * q.x, k * q.y, k * q.z};
}

inline q128 exp(const std::array<f128, 3>& v) {
    const f128 a = sqrtq(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (a == 0) return {};
    const f128 k = sinq(a) / a;
    return {cosq(a), k * v[0], k * v[1], k * v[2]};
}

inline q128 squad_control(const q128& prev, const q128& cur, const q128& next) {
    const auto l1 = log(mul(conj(cur), next)), l2 = log(mul(conj(cur), prev));
    return mul(cur, exp({-(l1[0] + l2[0]) / 4, -(l1[1] + l2[1]) / 4, -(l1[2] + l2[2]) / 4}));
}

}  // namespace keyrot::ref
