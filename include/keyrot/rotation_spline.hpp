#pragma once
// The rotation spline with continuous angular velocity and acceleration
// (--method cubic): the curve of scipy's RotationSpline, after N. Mayorov,
// "Smooth attitude interpolation" (2019).
#include <cstddef>
#include <span>
#include <vector>

#include "keyrot/quat.hpp"

namespace keyrot {

/// The body-frame angular velocity (radians per second) at each key of the
/// rotation spline through `keys` at `times`. On each segment the rotation
/// is key i times exp(phi(t)), phi a cubic in t - t_i with phi(t_i) = 0,
/// ending at the segment's rotation vector the short way, with the
/// velocities given at both keys; inner keys' velocities make the angular
/// acceleration continuous, the first and last keys' are the first and last
/// segments' mean rates. Two keys: that mean rate at both (slerp).
/// The equations are non-linear; solved as scipy does (a block tridiagonal
/// system, repeated with the curvature term of the last solution), or by
/// Newton's method where that converges slowly, until no velocity moves by
/// more than 1e-13 (1 + |w|) rad/s, or at most spline_max_rounds times.
/// Holds about 600 bytes a key while it solves. Preconditions: at least
/// two keys, times strictly increasing, keys unit.
struct spline_rates {
    std::vector<vec3> velocity;  ///< one per key
    bool converged = true;       ///< within the bound above
    int rounds = 0;              ///< how many the solution took
};
spline_rates spline_key_rates(std::span<const double> times, std::span<const quat> keys);

inline constexpr int spline_max_rounds = 100;

/// A segment of the spline: key q0 at t0 to key q1 = q0 exp(phi) at t0 + dt,
/// with velocities w0 and w1 at its keys.
class spline_segment {
public:
    spline_segment() = default;
    spline_segment(quat q0, quat q1, double dt, vec3 w0, vec3 w1) noexcept;
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
