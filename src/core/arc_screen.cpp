// SPDX-License-Identifier: MIT
#include "core/arc_screen.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace keyrot {

namespace {

// The verdicts' margins from the tolerance, on the sine of the angle.
constexpr double absolute = 1e-13, relative = 1e-9;

}  // namespace

double arc_screen::sin_half(double tol_deg) noexcept {
    // A rotation's angle is twice the angle between its quaternions.
    return tol_deg >= 0 && tol_deg <= 90 ? std::sin(tol_deg * std::numbers::pi / 360) : NAN;
}

arc_screen::arc_screen(quat a, quat b, double sin_half_tol) noexcept : a_(a), d_(dot(a, b)) {
    // In double precision, the arc's point at h and its distance from a key
    // are each within about 1e-15 of exact, where the arc is at most a
    // quarter circle (keys at most 180 degrees of rotation apart): w / |w|
    // may be off by 1e-16 / |w|, but it is scaled by sin(h theta) <= |w|.
    // The exact comparison is as close. The verdicts keep a margin of 1e-13
    // (and a billionth of the tolerance) from the tolerance: what is unsure
    // is the exact comparison's to make.
    w_ = {b.w - d_ * a.w, b.x - d_ * a.x, b.y - d_ * a.y, b.z - d_ * a.z};
    sin_theta_ = std::sqrt(dot(w_, w_));
    if (!(d_ > 0 && sin_theta_ > 0 && sin_half_tol >= 0)) return;
    inv_sin_theta_ = 1 / sin_theta_;
    const double within = sin_half_tol * (1 - relative) - absolute;
    const double beyond = sin_half_tol * (1 + relative) + absolute;
    within_sq_ = within > 0 ? within * within : -1;
    beyond_sq_ = beyond * beyond;
    // The great circle's plane, through a and w / |w|, is unsure by about
    // 1e-15 / |w| where w is short (a and b close): so is a key's distance
    // from it, and the margin widens (past any key, for the shortest arcs).
    const double off_circle = beyond + 2e-14 * inv_sin_theta_;
    off_circle_sq_ = off_circle * off_circle;
    usable_ = true;
}

arc_screen::finding arc_screen::at(double h, quat k) noexcept {
    if (!usable_) return {verdict::unsure, 1};
    if (theta_ < 0) {
        // A key farther than the tolerance from the plane of the arc's great
        // circle is as far from the line through any point of the arc.
        const double p = dot(k, a_), q = dot(k, w_) * inv_sin_theta_ * inv_sin_theta_;
        const quat r{k.w - p * a_.w - q * w_.w, k.x - p * a_.x - q * w_.x, k.y - p * a_.y - q * w_.y,
                     k.z - p * a_.z - q * w_.z};
        if (dot(r, r) > off_circle_sq_) return {verdict::beyond, 1};
        theta_ = std::atan2(sin_theta_, d_);
    }
    const double phi = h * theta_;
    const double c0 = std::cos(phi), s = std::sin(phi) * inv_sin_theta_;
    const quat c{c0 * a_.w + s * w_.w, c0 * a_.x + s * w_.x, c0 * a_.y + s * w_.y, c0 * a_.z + s * w_.z};
    // The sine of the angle between k and the line through c (k and -k are one rotation), squared.
    const double t = dot(k, c);
    const quat r{k.w - t * c.w, k.x - t * c.x, k.y - t * c.y, k.z - t * c.z};
    const double sin_off_sq = dot(r, r);
    if (sin_off_sq < within_sq_) return {verdict::within, sin_off_sq};
    if (sin_off_sq > beyond_sq_) return {verdict::beyond, sin_off_sq};
    return {verdict::unsure, sin_off_sq};
}

double arc_screen::most_deg(double sin_off_sq) noexcept {
    return 360 / std::numbers::pi * std::asin(std::min(1.0, std::sqrt(sin_off_sq) + absolute)) * (1 + relative);
}

}  // namespace keyrot
