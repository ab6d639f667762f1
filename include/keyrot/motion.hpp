// SPDX-License-Identifier: MIT
#pragma once
// How fast a rotation turns at an instant: its angular velocity and
// acceleration, in the body frame (what a gyroscope on the object reads)
// or the fixed frame, and the SO(3) calculus that gives them for a
// rotation written as a key times exp(rotation vector).
#include <array>

#include "keyrot/names.hpp"
#include "keyrot/quat.hpp"

namespace keyrot {

/// Angular velocity (radians per second) and acceleration (radians per
/// second squared).
struct motion {
    vec3 velocity, acceleration;
};

/// The frame motion is expressed in: the rotating body's own axes, as a
/// gyroscope on it reads (and scipy's RotationSpline reports), or the fixed
/// (world) axes.
enum class motion_frame { body, fixed };
template <>
inline constexpr std::array<enum_name<motion_frame>, 2> names_of<motion_frame> = {
    {{motion_frame::body, "body"}, {motion_frame::fixed, "world"}}};

/// The body-frame motion of rotation q, in the fixed frame: R(q) w and R(q) a
/// (the fixed frame's acceleration is the turned body one: R' w = R (w x w) = 0).
motion in_fixed_frame(quat q, const motion& body) noexcept;

/// For a rotation R exp(phi) with phi a rotation vector (radians) that
/// moves: the body-frame angular velocity is rate_matrix(phi) phi' (the
/// right Jacobian of SO(3)), and phi' = inverse_rate_matrix(phi) w.
/// rate_matrix({0, 0, 0}) is the identity.
mat3 rate_matrix(vec3 phi) noexcept;
mat3 inverse_rate_matrix(vec3 phi) noexcept;
/// The angular acceleration's term in phi' alone: the acceleration is
/// rate_matrix(phi) phi'' + rate_curvature(phi, phi'). Zero for phi parallel to phi'.
vec3 rate_curvature(vec3 phi, vec3 phi_dot) noexcept;
/// The same in two steps, for many phi' at one phi: its coefficients (of
/// phi's angle alone), then the term.
struct curvature_coefficients {
    double a1 = 0, a2 = 0, a3 = 0;
};
curvature_coefficients curvature_of(vec3 phi) noexcept;
vec3 rate_curvature(vec3 phi, vec3 phi_dot, const curvature_coefficients& k) noexcept;
/// The derivative of rate_curvature(phi, v) in v (phi fixed), for Newton's method.
mat3 curvature_jacobian(vec3 phi, vec3 v, const curvature_coefficients& k) noexcept;

/// A quaternion and its first two derivatives in time (per second).
struct quat_jet {
    quat q, d1{0, 0, 0, 0}, d2{0, 0, 0, 0};
};
/// The product rule: (ab, a'b + ab', a''b + 2a'b' + ab'').
quat_jet operator*(const quat_jet& a, const quat_jet& b) noexcept;
/// q / |q| with its derivatives. Precondition: q non-zero.
quat_jet normalized_jet(const quat_jet& j) noexcept;
/// The body-frame motion of a unit quaternion's jet: w = 2 vec(q* q'), a = 2 vec(q* q'').
motion motion_of(const quat_jet& j) noexcept;
/// The body-frame motion of key exp(phi) (any key) as phi moves:
/// rate_matrix(phi) phi' and rate_matrix(phi) phi'' + rate_curvature(phi, phi').
motion motion_of(vec3 phi, vec3 phi_dot, vec3 phi_ddot) noexcept;

/// m v, m + n, s m, m n for the matrices above.
vec3 operator*(const mat3& m, vec3 v) noexcept;
mat3 operator+(const mat3& a, const mat3& b) noexcept;
mat3 operator*(double s, const mat3& m) noexcept;
mat3 operator*(const mat3& a, const mat3& b) noexcept;
/// The inverse of a non-singular m.
mat3 inverse(const mat3& m) noexcept;

}  // namespace keyrot
