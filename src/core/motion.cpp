// SPDX-License-Identifier: MIT
#include "keyrot/motion.hpp"

#include <cmath>

#include "keyrot/convert.hpp"

namespace keyrot {
namespace {

/// Below this angle (radians) the coefficients are summed from their Taylor
/// series in theta^2 (where their closed forms cancel), to a term below
/// 1e-17 of the sum.
constexpr double series_below = 1;

/// c[0] + c[1] s + c[2] s^2 + ...
template <std::size_t N>
double series(const double (&c)[N], double s) noexcept {
    double sum = 0;
    for (std::size_t i = N; i-- > 0;) sum = sum * s + c[i];
    return sum;
}

// (1 - cos t)/t^2, (t - sin t)/t^3, (1 - (t/2) cot(t/2))/t^2 (its terms
// Bernoulli numbers'), (2 - 2 cos t - t sin t)/t^4, (3 sin t - t cos t - 2t)/t^5.
constexpr double one_minus_cos[] = {
    1. / 2., -1. / 24., 1. / 720., -1. / 40320., 1. / 3628800., -1. / 479001600., 1. / 87178291200.,
    -1. / 20922789888000., 1. / 6402373705728000.};
constexpr double t_minus_sin[] = {
    1. / 6., -1. / 120., 1. / 5040., -1. / 362880., 1. / 39916800., -1. / 6227020800., 1. / 1307674368000.,
    -1. / 355687428096000., 1. / 121645100408832000.};
constexpr double half_cot[] = {
    1. / 12., 1. / 720., 1. / 30240., 1. / 1209600., 1. / 47900160., 691. / 1307674368000., 1. / 74724249600.,
    3617. / 10670622842880000., 43867. / 5109094217170944000., 174611. / 802857662698291200000.,
    77683. / 14101100039391805440000.};
constexpr double curvature_1[] = {
    1. / 12., -1. / 180., 1. / 6720., -1. / 453600., 1. / 47900160., -1. / 7264857600., 1. / 1494484992000.,
    -1. / 400148356608000., 1. / 135161222676480000., -1. / 56200036388880384000.};
constexpr double curvature_2[] = {
    -1. / 60., 1. / 1260., -1. / 60480., 1. / 4989600., -1. / 622702080., 1. / 108972864000., -1. / 25406244864000.,
    1. / 7602818775552000., -1. / 2838385676206080000., 1. / 1292600836944248832000.};

/// [v]x, the cross product matrix: [v]x u = v x u.
mat3 skew(vec3 v) noexcept { return {{{{0, -v.z, v.y}, {v.z, 0, -v.x}, {-v.y, v.x, 0}}}}; }

mat3 identity() noexcept { return {{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}}; }


}  // namespace

vec3 operator*(const mat3& m, vec3 v) noexcept {
    const auto& a = m.m;
    return {a[0][0] * v.x + a[0][1] * v.y + a[0][2] * v.z, a[1][0] * v.x + a[1][1] * v.y + a[1][2] * v.z,
            a[2][0] * v.x + a[2][1] * v.y + a[2][2] * v.z};
}

mat3 operator+(const mat3& a, const mat3& b) noexcept {
    mat3 r;
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j) r.m[i][j] = a.m[i][j] + b.m[i][j];
    return r;
}

mat3 operator*(double s, const mat3& m) noexcept {
    mat3 r;
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j) r.m[i][j] = s * m.m[i][j];
    return r;
}

mat3 operator*(const mat3& a, const mat3& b) noexcept {
    mat3 r;
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j) r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j];
    return r;
}

mat3 inverse(const mat3& m) noexcept {
    const auto& a = m.m;
    mat3 r;  // the adjugate over the determinant
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j) {
            const std::size_t i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
            r.m[i][j] = a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1];
        }
    const double det = a[0][0] * r.m[0][0] + a[0][1] * r.m[1][0] + a[0][2] * r.m[2][0];
    return (1 / det) * r;
}

motion in_fixed_frame(quat q, const motion& body) noexcept {
    return {rotate(q, body.velocity), rotate(q, body.acceleration)};
}

mat3 rate_matrix(vec3 phi) noexcept {
    // I - (1 - cos t)/t^2 [phi]x + (t - sin t)/t^3 [phi]x^2
    const double t = norm(phi), s = t * t;
    const bool small = t < series_below;
    const double k1 = small ? series(one_minus_cos, s) : (1 - std::cos(t)) / s;
    const double k2 = small ? series(t_minus_sin, s) : (t - std::sin(t)) / (s * t);
    const mat3 k = skew(phi);
    return identity() + (-k1) * k + k2 * (k * k);
}

mat3 inverse_rate_matrix(vec3 phi) noexcept {
    // I + [phi]x / 2 + (1 - (t/2) cot(t/2))/t^2 [phi]x^2
    const double t = norm(phi), s = t * t;
    const double k = t < series_below ? series(half_cot, s) : (1 - 0.5 * t / std::tan(0.5 * t)) / s;
    const mat3 m = skew(phi);
    return identity() + 0.5 * m + k * (m * m);
}

curvature_coefficients curvature_of(vec3 phi) noexcept {
    const double t = norm(phi), s = t * t;
    if (t < series_below) return {series(curvature_1, s), series(curvature_2, s), series(t_minus_sin, s)};
    const double sin_t = std::sin(t), cos_t = std::cos(t);
    return {(2 - 2 * cos_t - t * sin_t) / (s * s), (3 * sin_t - t * cos_t - 2 * t) / (s * s * t), (t - sin_t) / (s * t)};
}

vec3 rate_curvature(vec3 phi, vec3 phi_dot, const curvature_coefficients& k) noexcept {
    // (phi . phi') (a1 phi x phi' + a2 phi x (phi x phi')) + a3 phi' x (phi x phi'):
    // the derivative of rate_matrix(phi) along phi', applied to phi'.
    const vec3 c = cross(phi, phi_dot);
    return dot(phi, phi_dot) * (k.a1 * c + k.a2 * cross(phi, c)) + k.a3 * cross(phi_dot, c);
}

mat3 curvature_jacobian(vec3 phi, vec3 v, const curvature_coefficients& k) noexcept {
    // d/dv of (phi . v)(a1 Pv + a2 PPv) + a3 v x Pv, P = [phi]x:
    // (a1 Pv + a2 PPv) phi^T + (phi . v)(a1 P + a2 PP) + a3 ([v]x P - [Pv]x)
    const mat3 p = skew(phi), pp = p * p;
    const vec3 pv = cross(phi, v), bent = k.a1 * pv + k.a2 * cross(phi, pv);
    mat3 outer;
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j)
            outer.m[i][j] = (i == 0 ? bent.x : i == 1 ? bent.y : bent.z) * (j == 0 ? phi.x : j == 1 ? phi.y : phi.z);
    return outer + dot(phi, v) * (k.a1 * p + k.a2 * pp) + k.a3 * (skew(v) * p + (-1.0) * skew(pv));
}

vec3 rate_curvature(vec3 phi, vec3 phi_dot) noexcept { return rate_curvature(phi, phi_dot, curvature_of(phi)); }

quat_jet operator*(const quat_jet& a, const quat_jet& b) noexcept {
    return {a.q * b.q, a.d1 * b.q + a.q * b.d1, a.d2 * b.q + 2.0 * (a.d1 * b.d1) + a.q * b.d2};
}

quat_jet normalized_jet(const quat_jet& j) noexcept {
    // j.q = n u: j.d1 = n' u + n u', j.d2 = n'' u + 2 n' u' + n u'', with
    // n' = u . j.d1 and n'' = u' . j.d1 + u . j.d2.
    const double n = norm(j.q);
    const quat u = (1 / n) * j.q;
    const double n1 = dot(u, j.d1);
    const quat u1 = (1 / n) * (j.d1 + (-n1) * u);
    const double n2 = dot(u1, j.d1) + dot(u, j.d2);
    return {u, u1, (1 / n) * (j.d2 + (-n2) * u + (-2 * n1) * u1)};
}

motion motion_of(const quat_jet& j) noexcept {
    // (q* q')' = q*' q' + q* q'', and q*' q' = |q'|^2 has no vector part.
    const quat c = conjugate(j.q);
    return {2.0 * vector_part(c * j.d1), 2.0 * vector_part(c * j.d2)};
}

motion motion_of(vec3 phi, vec3 phi_dot, vec3 phi_ddot) noexcept {
    const mat3 j = rate_matrix(phi);
    return {j * phi_dot, j * phi_ddot + rate_curvature(phi, phi_dot)};
}

}  // namespace keyrot
