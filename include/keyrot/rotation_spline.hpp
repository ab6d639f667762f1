// SPDX-License-Identifier: MIT
#pragma once
// The rotation spline with continuous angular velocity and acceleration
// (method::cubic): the curve of scipy's RotationSpline, after N. Mayorov,
// "Smooth attitude interpolation" (2019).
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "keyrot/quat.hpp"

namespace keyrot {

/// How a solve of the spline's equations went.
struct spline_status {
    bool converged = true;  ///< within the bound below
    int rounds = 0;         ///< how many the solution took
};

inline constexpr int spline_max_rounds = 100;

/// The rotation spline through keys: on each segment the rotation is key i
/// times exp(phi(t)), phi a cubic in t - t_i with phi(t_i) = 0, ending at
/// the segment's rotation vector the short way, with the body-frame angular
/// velocities (radians per second) given at both keys. The inner keys'
/// velocities make the angular acceleration continuous; the first and last
/// keys' are fixed. The equations are non-linear; solved as scipy does (a
/// block tridiagonal system, repeated with the curvature term of the last
/// solution), or by Newton's method where that converges slowly, until no
/// velocity moves by more than 1e-13 (1 + |w|) rad/s, or at most
/// spline_max_rounds times. It keeps its buffers from stretch to stretch
/// (a copy starts without them).
class spline_solver {
public:
    spline_solver();
    ~spline_solver();
    spline_solver(const spline_solver&);
    spline_solver& operator=(const spline_solver&);
    /// `phi`: each segment's rotation vector (rotation_vector_between its
    /// keys); `velocity`: one per key, the first and last fixed, the others
    /// a first guess, solved in place. Preconditions: at least three keys,
    /// times strictly increasing.
    spline_status solve(std::span<const double> times, std::span<const vec3> phi, std::span<vec3> velocity);

private:
    struct workspace;
    std::unique_ptr<workspace> work_;
};

/// A whole track's spline, its end velocities the first and last segments'
/// mean rates (scipy's RotationSpline): the velocity at each key. Two keys: the mean rate at both (slerp).
struct spline_rates {
    std::vector<vec3> velocity;
    spline_status status;
};
spline_rates spline_key_rates(std::span<const double> times, std::span<const quat> keys);

/// The rotation vector (radians) from unit a to unit b, the short way:
/// b = a exp(phi) with |phi| at most pi.
vec3 rotation_vector_between(quat a, quat b) noexcept;

/// A segment of the spline: key q0 at t0 to key q0 exp(phi) at t0 + dt
/// (phi = rotation_vector_between the keys), with velocities w0 and w1 at its keys.
class spline_segment {
public:
    spline_segment() = default;
    spline_segment(quat q0, vec3 phi, double dt, vec3 w0, vec3 w1) noexcept;
    /// The rotation at local parameter h in [0, 1]: q0 exp(phi(h dt)).
    quat at(double h) const noexcept;
    /// phi, phi' and phi'' (per second) at local parameter h.
    struct point {
        vec3 phi, phi_dot, phi_ddot;
    };
    point derivatives(double h) const noexcept;

private:
    quat q0_;
    double dt_ = 1;
    vec3 c1_, c2_, c3_;  // phi(s) = ((c3 s + c2) s + c1) s, s = h dt
};

}  // namespace keyrot
