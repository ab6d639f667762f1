// SPDX-License-Identifier: MIT
#pragma once
// A quick test of keys against the slerp arc between two keys, for reduce's
// probes: most keys are far inside or far outside the tolerance, and only
// the ones near it need the exact curve (slerp_segment) to decide.
#include "keyrot/quat.hpp"

namespace keyrot {

class arc_screen {
public:
    enum class verdict { within, beyond, unsure };
    /// What every screen of a tolerance in degrees of rotation shares: the
    /// sine of half of it, or NaN for a tolerance over 90 degrees (or none),
    /// where no verdict is sure.
    static double sin_half(double tol_deg) noexcept;
    /// The arc from a to b (unit, with the signs the path gave them), for
    /// the tolerance whose sin_half is given.
    arc_screen(quat a, quat b, double sin_half_tol) noexcept;
    /// False where the screen cannot help and every verdict is unsure: a and
    /// b 180 degrees of rotation apart or more (the long way round) or the
    /// same, a tolerance over 90 degrees.
    bool usable() const noexcept { return usable_; }
    struct finding {
        verdict v;
        // The square of the sine of the angle between k and the arc's point
        // (half the rotation's); 1 for a key found off the arc's great circle.
        double sin_off_sq;
    };
    /// Whether unit key k is within the tolerance of the arc's point at h in
    /// [0, 1], as the exact comparison (geodesic_angle with slerp_segment's
    /// point, in degrees, <= the tolerance) would find; unsure near the
    /// tolerance, where the rounding of either could tip it. Not const: the
    /// arc's angle is worked out for the first key that is not plainly off
    /// the arc's great circle, so a probe that fails at once pays no atan2.
    finding at(double h, quat k) noexcept;
    /// At least the exact comparison's angle, in degrees, for a key whose
    /// finding had `sin_off_sq` (or the largest of several); most_deg(0) is
    /// the least bound a screen gives.
    static double most_deg(double sin_off_sq) noexcept;

private:
    quat a_, w_;        // the arc: cos(h theta) a + sin(h theta) w / |w|, w = b - (a.b) a
    double d_ = 0;      // a.b, the cosine of theta
    double sin_theta_ = 0, inv_sin_theta_ = 0;
    double theta_ = -1;  // the arc's angle on the unit sphere of quaternions (half the rotation's); -1 until needed
    // Squares of sines of the angle from the arc's point: verdicts below and
    // above; beyond the great circle: above (its plane is less sure).
    double within_sq_ = -1, beyond_sq_ = 0, off_circle_sq_ = 0;
    bool usable_ = false;
};

}  // namespace keyrot
