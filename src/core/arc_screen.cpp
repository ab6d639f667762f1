#include "core/arc_screen.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace keyrot {

namespace {

// The verdicts' margins from the tolerance, on the sine of the angle.
constexpr double absolute = 1e-13, relative = 1e-9;

}  // namespace

arc_screen::arc_screen(quat a, quat b, double tol_deg) noexcept : a_(a) {
    // In double precision, the arc's point at h and its distance from a key
    // are each within about 1e-15 of exact, where the arc is at most a
    // quarter circle (keys at most 180 degrees of rotation apart): w / |w|
    // may be off by 1e-16 / |w|, but it is scaled by sin(h theta) <= |w|.
    // The exact comparison is as close. The verdicts keep a margin of 1e-13
    // (and a billionth of the tolerance) from the tolerance: what is unsure
    // is the exact comparison's to make.
    const double d = dot(a, b);
    w_ = {b.w - d * a.w, b.x - d * a.x, b.y - d * a.y, b.z - d * a.z};
    const double sin_theta = std::sqrt(dot(w_, w_));
    if (!(d > 0 && sin_theta > 0 && tol_deg >= 0 && tol_deg <= 90)) return;
    theta_ = std::atan2(sin_theta, d);
    inv_sin_theta_ = 1 / sin_theta;
    // A rotation's angle is twice the angle between its quaternions.
    const double sin_tol = std::sin(tol_deg * std::numbers::pi / 360);
    within_ = sin_tol * (1 - relative) - absolute;
    beyond_ = sin_tol * (1 + relative) + absolute;
    usable_ = true;
}

arc_screen::finding arc_screen::at(double h, quat k) const noexcept {
    if (!usable_) return {verdict::unsure, 1};
    const double phi = h * theta_;
    const double c0 = std::cos(phi), s = std::sin(phi) * inv_sin_theta_;
    const quat c{c0 * a_.w + s * w_.w, c0 * a_.x + s * w_.x, c0 * a_.y + s * w_.y, c0 * a_.z + s * w_.z};
    // The sine of the angle between k and the line through c (k and -k are one rotation).
    const double t = dot(k, c);
    const quat r{k.w - t * c.w, k.x - t * c.x, k.y - t * c.y, k.z - t * c.z};
    const double sin_off = std::sqrt(dot(r, r));
    if (sin_off < within_) return {verdict::within, sin_off};
    if (sin_off > beyond_) return {verdict::beyond, sin_off};
    return {verdict::unsure, sin_off};
}

double arc_screen::most_deg(double sin_off) const noexcept {
    return 360 / std::numbers::pi * std::asin(std::min(1.0, sin_off + absolute)) * (1 + relative);
}

}  // namespace keyrot
