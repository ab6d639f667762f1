// SPDX-License-Identifier: MIT
#pragma once
// Quaternions, 3-vectors and 3x3 matrices: the value types every stage shares.
//
// A quat is w + xi + yj + zk, stored in (w, x, y, z) order everywhere inside
// keyrot; only the readers and writers know about --quat-order. Products are
// Hamilton's (ij = k), rotations are active on column vectors, and q and -q
// are the same rotation.
#include <array>

namespace keyrot {

struct vec3 {
    double x = 0, y = 0, z = 0;
};

struct quat {
    double w = 1, x = 0, y = 0, z = 0;
};

/// Row-major 3x3 matrix: m[row][col].
struct mat3 {
    std::array<std::array<double, 3>, 3> m{};
};

/// {1, 2, 3} + {1, 1, 1} = {2, 3, 4}.
vec3 operator+(vec3 a, vec3 b) noexcept;
/// {1, 2, 3} - {1, 1, 1} = {0, 1, 2}.
vec3 operator-(vec3 a, vec3 b) noexcept;
/// 2 * {1, 2, 3} = {2, 4, 6}.
vec3 operator*(double s, vec3 v) noexcept;
/// dot({1, 2, 3}, {4, 5, 6}) = 32.
double dot(vec3 a, vec3 b) noexcept;
/// cross({1, 0, 0}, {0, 1, 0}) = {0, 0, 1}.
vec3 cross(vec3 a, vec3 b) noexcept;
/// Euclidean length without overflow or underflow (|(1e-200, 0, 0)| = 1e-200).
double norm(vec3 v) noexcept;

/// Component-wise, for derivatives of quaternions (motion.hpp):
/// {1, 0, 0, 0} + {0, 1, 0, 0} = {1, 1, 0, 0}; 2 * {1, 0, 0, 0} = {2, 0, 0, 0}.
quat operator+(quat a, quat b) noexcept;
quat operator*(double s, quat q) noexcept;
/// -q, the same rotation: -{1, 0, 0, 0} = {-1, 0, 0, 0}.
quat operator-(quat q) noexcept;
/// Hamilton product: a*b applies b first. Each component is summed in twice
/// the working precision and rounded once, so conjugate(a) * b stays accurate
/// when a and b are nearly equal or nearly opposite, where a plain sum cancels.
quat operator*(quat a, quat b) noexcept;
/// The 4-d dot product: |dot(a, b)| = cos(half the angle between a and b) for unit a, b.
double dot(quat a, quat b) noexcept;
/// Euclidean length, as norm(vec3): norm({2, 0, 0, 0}) = 2.
double norm(quat q) noexcept;
/// (w, -x, -y, -z): the inverse of a unit quaternion, q * conjugate(q) = identity.
quat conjugate(quat q) noexcept;

/// x0 y0 + ... + x(n-1) y(n-1) as if computed in twice the precision and
/// rounded once (Ogita, Rump and Oishi's Dot2: error-free products and sums).
/// dot2({1e16, 1, -1e16}, {1, 1, 1}) = 1, where a plain sum gives 0.
template <std::size_t N>
double dot2(const double (&x)[N], const double (&y)[N]) noexcept;
extern template double dot2<2>(const double (&)[2], const double (&)[2]) noexcept;
extern template double dot2<3>(const double (&)[3], const double (&)[3]) noexcept;
extern template double dot2<4>(const double (&)[4], const double (&)[4]) noexcept;
/// vector_part({w, x, y, z}) = {x, y, z}.
vec3 vector_part(quat q) noexcept;

/// q / |q|. Precondition: q is finite and non-zero.
quat normalized(quat q) noexcept;
/// The same, given n = norm(q): a caller that has the norm already saves
/// working it out again (a square root, whose latency is most of a norm).
quat normalized(quat q, double n) noexcept;
/// v or q times the power of two that puts its largest component in [1, 2):
/// exactly the same direction, with a length that can neither pass the
/// largest double nor lose digits among the subnormals; zero comes back
/// zero. rescaled({1e-300, 0, 0}) = {2^997 * 1e-300, 0, 0}, about 1.34.
vec3 rescaled(vec3 v) noexcept;
/// As rescaled(vec3): rescaled({4, 0, 0, 0}) = {1, 0, 0, 0}.
quat rescaled(quat q) noexcept;

/// Exponential of the pure quaternion (0, v): (cos|v|, sin|v| v/|v|).
/// exp({0, 0, pi/4}) = 90 degrees about z.
quat exp(vec3 v) noexcept;

/// Logarithm of a unit quaternion: v with exp(v) = q and |v| in [0, pi].
/// For q = (-1, 0, 0, 0) the direction is undefined; keyrot picks +x.
vec3 log(quat q) noexcept;

/// Rotation angle in [0, pi] of the rotation taking a to b (sign-invariant:
/// a and -a give the same answer). geodesic_angle(q, q) = 0.
double geodesic_angle(quat a, quat b) noexcept;
/// geodesic_angle in two steps, for a caller that can do without the
/// angle of most pairs: the sine and cosine of half of it, to one scale
/// (the vector part's norm and |w| of conjugate(a) * b), then the angle.
struct half_angle {
    double sin, cos;
};
half_angle geodesic_half_angle(quat a, quat b) noexcept;
double geodesic_angle(half_angle h) noexcept;

/// Rotate v by the unit quaternion q (v' = R v).
vec3 rotate(quat q, vec3 v) noexcept;

}  // namespace keyrot
