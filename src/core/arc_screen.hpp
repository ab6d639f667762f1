#pragma once
// A quick test of keys against the slerp arc between two keys, for reduce's
// probes: most keys are far inside or far outside the tolerance, and only
// the ones near it need the exact curve (slerp_segment) to decide.
#include "keyrot/quat.hpp"

namespace keyrot {

class arc_screen {
public:
    enum class verdict { within, beyond, unsure };
    /// The arc from a to b (unit, with the signs the path gave them) and a
    /// tolerance in degrees of rotation.
    arc_screen(quat a, quat b, double tol_deg) noexcept;
    /// False where the screen cannot help and every verdict is unsure: a and
    /// b 180 degrees of rotation apart or more (the long way round) or the
    /// same, a tolerance over 90 degrees.
    bool usable() const noexcept { return usable_; }
    struct finding {
        verdict v;
        double sin_off;  // the sine of the angle between k and the arc's point (half the rotation's)
    };
    /// Whether unit key k is within the tolerance of the arc's point at h in
    /// [0, 1], as the exact comparison (geodesic_angle with slerp_segment's
    /// point, in degrees, <= the tolerance) would find; unsure near the
    /// tolerance, where the rounding of either could tip it.
    finding at(double h, quat k) const noexcept;
    /// At least the exact comparison's angle, in degrees, for a key whose
    /// finding had `sin_off` (or the largest of several).
    double most_deg(double sin_off) const noexcept;

private:
    quat a_, w_;        // the arc: cos(h theta) a + sin(h theta) w / |w|, w = b - (a.b) a
    double theta_ = 0;  // the arc's angle on the unit sphere of quaternions (half the rotation's)
    double inv_sin_theta_ = 0;
    double within_ = 0, beyond_ = 0;  // sine of the angle from the arc's point: verdicts below and above
    bool usable_ = false;
};

}  // namespace keyrot
