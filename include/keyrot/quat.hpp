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

// vec3 arithmetic
vec3 operator+(vec3 a, vec3 b) noexcept;
vec3 operator-(vec3 a, vec3 b) noexcept;
vec3 operator*(double s, vec3 v) noexcept;
double dot(vec3 a, vec3 b) noexcept;
vec3 cross(vec3 a, vec3 b) noexcept;
/// Euclidean length without overflow or underflow (|(1e-200, 0, 0)| = 1e-200).
double norm(vec3 v) noexcept;

// quat arithmetic
quat operator-(quat q) noexcept;
/// Hamilton product: a*b applies b first. Each component is summed in twice
/// the working precision and rounded once, so conjugate(a) * b stays accurate
/// when a and b are nearly equal or nearly opposite, where a plain sum cancels.
quat operator*(quat a, quat b) noexcept;
double dot(quat a, quat b) noexcept;
double norm(quat q) noexcept;
quat conjugate(quat q) noexcept;  ///< the inverse, for a unit quaternion

/// x0 y0 + ... + x(n-1) y(n-1) as if computed in twice the precision and
/// rounded once (Ogita, Rump and Oishi's Dot2: error-free products and sums).
template <std::size_t N>
double dot2(const double (&x)[N], const double (&y)[N]) noexcept;
extern template double dot2<2>(const double (&)[2], const double (&)[2]) noexcept;
extern template double dot2<3>(const double (&)[3], const double (&)[3]) noexcept;
extern template double dot2<4>(const double (&)[4], const double (&)[4]) noexcept;
vec3 vector_part(quat q) noexcept;

/// q / |q|. Precondition: q is finite and non-zero.
quat normalized(quat q) noexcept;
/// v or q times the power of two that puts its largest component in [1, 2):
/// exactly the same direction, with a length that can neither pass the
/// largest double nor lose digits among the subnormals. Precondition:
/// finite and non-zero.
vec3 rescaled(vec3 v) noexcept;
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

/// Rotate v by the unit quaternion q (v' = R v).
vec3 rotate(quat q, vec3 v) noexcept;

}  // namespace keyrot
