// SPDX-License-Identifier: MIT
#pragma once
// Interpolation methods: the kernels (slerp, nlerp, squad) and the curve
// through a track's keys that resample evaluates segment by segment.
#include <array>
#include <optional>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

#include "keyrot/convert.hpp"
#include "keyrot/method.hpp"
#include "keyrot/motion.hpp"
#include "keyrot/quat.hpp"
#include "keyrot/rotation_spline.hpp"
#include "keyrot/track.hpp"

namespace keyrot {

/// Throws option_error for method::euler without an Euler sequence:
/// check_method(method::euler, std::nullopt) says "method euler needs an Euler sequence".
void check_method(method m, const std::optional<euler_seq>& seq);

/// glTF's cubic Hermite spline (the glTF 2.0 specification's CUBICSPLINE
/// interpolation) between values v0 at s = 0 and v1 at s = 1,
/// with tangents b0 (v0's out-tangent) and a1 (v1's in-tangent) per second,
/// over a key interval of `seconds`: (2s^3 - 3s^2 + 1) v0 + seconds (s^3 -
/// 2s^2 + s) b0 + (-2s^3 + 3s^2) v1 + seconds (s^3 - s^2) a1, component-wise.
std::array<double, 4> hermite(const std::array<double, 4>& v0, const std::array<double, 4>& b0,
                              const std::array<double, 4>& v1, const std::array<double, 4>& a1, double seconds,
                              double s) noexcept;
/// The same for any number of components (out.size() of them, and as many
/// in each of the others).
void hermite(std::span<const double> v0, std::span<const double> b0, std::span<const double> v1,
             std::span<const double> a1, double seconds, double s, std::span<double> out) noexcept;

/// Spherical linear interpolation from a to b, prepared once per pair of
/// keys: Algorithm 2.1 of Szeliski's *Computer Vision: Algorithms and
/// Applications* (2nd ed., 2022), with the relative rotation's axis and
/// angle lifted out of the per-frame loop, the angle kept to twice the
/// working precision so that the result is within about 2x of correctly
/// rounded even on the long way round.
class slerp_segment {
public:
    slerp_segment() = default;
    slerp_segment(quat a, quat b) noexcept;
    /// Constant angular speed, no sign flip (a and b as given, so b = -a
    /// turns a full 360 degrees, about a's local x). Exact at h = 0 and 1.
    quat at(double h) const noexcept;
    /// The rotation vector (radians) it turns, a to b: its angular velocity times the segment's duration.
    vec3 rotation_vector() const noexcept;

private:
    quat a_, b_;
    long double axis_x_ = 1, axis_y_ = 0, axis_z_ = 0;  // of conjugate(a) * b
    double half_ = 0, half_lo_ = 0;                     // its half angle, as hi + lo
};

/// slerp_segment(a, b).at(h). slerp(1, 90deg@z, 0.5) = 45deg@z.
quat slerp(quat a, quat b, double h) noexcept;
/// Lerp of the components, normalised ("nlerp"). If the lerp
/// is zero (b = -a, h = 1/2) the rotation is a's. nlerp(1, 90deg@z, 0.5) =
/// 45deg@z, as slerp at the midpoint; elsewhere it runs ahead or behind.
quat nlerp(quat a, quat b, double h) noexcept;
/// Shoemake's control point (Animating Rotation with Quaternion Curves,
/// SIGGRAPH 1985): s_i = q_i exp(-(log(q_i^-1 q_next) + log(q_i^-1 q_prev)) / 4).
/// Keys evenly spaced on one great circle give s_i = q_i (squad is then slerp).
quat squad_control(quat prev, quat cur, quat next) noexcept;

class segment_curve;

/// Where `time` falls between keys at t0 and t1: the h every frame (and
/// every channel's value) is evaluated at, wherever that happens.
inline double segment_fraction(double t0, double t1, double time) noexcept { return (time - t0) / (t1 - t0); }

/// A slerp or squad segment's keys (as the path signed them) and squad's
/// control points: all its curve needs, small enough to hand to another
/// thread with the segment's frames (track_resampler's arc_frame_sink).
struct arc_keys {
    double t0 = 0, t1 = 0;
    quat q0, q1, s0, s1;  // s0, s1: squad's control points
    bool squad = false;   // else slerp
};

/// A slerp or squad segment's curve, its great-circle arcs set up once:
/// slerp(q0, q1, h), or Shoemake's slerp(slerp(q0, q1, h), slerp(s0, s1, h), 2h(1 - h)).
class arc_curve {
public:
    explicit arc_curve(const arc_keys& k) noexcept;
    quat at(double h) const noexcept;

private:
    friend class segment_curve;
    slerp_segment arc_;
    std::optional<slerp_segment> control_arc_;  // squad's
};

/// A cubic track whose spline's equations do not settle (steps near 180
/// degrees between keys of very uneven spacing: scipy's iteration fails there too).
struct spline_error : error {
    using error::error;
};

/// Two neighbouring keys and what a method needs of them.
class segment {
public:
    double t0 = 0, t1 = 0;  ///< the keys' times
    quat q0, q1;            ///< the keys, with the signs the path gave them
    /// The curve between them. Its set-up (slerp's angle and axis) costs as
    /// much as a few frames: make it once, and only for a segment with a
    /// frame inside.
    segment_curve curve() const noexcept;
    /// Its keys, and squad's control points (for methods slerp and squad only).
    arc_keys keys_for_arcs() const noexcept;

private:
    friend class segment_builder;
    friend class segment_curve;
    struct squad_points {  // squad: the control points
        quat s0, s1;
    };
    struct euler_angles {  // euler: the keys' angles
        std::array<double, 3> e0, e1;
        euler_seq seq;
    };
    struct spline_keys {  // cubicspline: the keys as the spline passes them
        spline_key k0, k1;
    };
    method how_ = method::slerp;
    // What the method needs beyond the keys, and nothing for the others: a
    // segment is made (and its curve copies it) for every key, and the
    // everyday methods' then take a few words.
    std::variant<std::monostate, squad_points, euler_angles, spline_keys, spline_segment> more_;
};

/// The curve between two neighbouring keys for one method, ready to evaluate.
class segment_curve {
public:
    /// The rotation at local parameter h in [0, 1].
    quat at(double h) const noexcept;
    /// The curve's exact angular velocity and acceleration there, in the
    /// body frame, per second (zero for step; slerp's velocity is constant).
    motion rates(double h) const noexcept;

private:
    friend class segment;
    explicit segment_curve(const segment& keys) noexcept : keys_(keys) {}
    segment keys_;
    std::optional<arc_curve> arcs_;  // slerp's and squad's
};

/// Turns a track's keys, as they arrive, into segments: the sign of each key
/// set by the path (cubicspline keeps the file's, which its tangents are
/// of; cubic always turns the short way, as scipy's RotationSpline does),
/// squad's control points (one key of look-ahead), Euler angles for
/// --method euler. Memory stays a few keys, but for cubic: its segments all
/// depend on every key, with an influence that falls off geometrically, so
/// it solves the spline a stretch of cubic_stretch keys at a time, each
/// with cubic_margin keys of look-ahead whose velocities it leaves to the
/// next stretch (docs/design.md: their effect is far below rounding), and
/// holds that many keys.
class segment_builder {
public:
    /// Throws option_error for method::euler without a sequence.
    segment_builder(method m, path p, const std::optional<euler_seq>& seq);
    /// Adds the next key (times strictly increasing); returns its rotation
    /// with the sign the path gave it.
    quat add(const key& k);
    /// The sign add() gives rotation q coming after a key whose rotation
    /// (with its sign) is `prev`, without adding it: for every method but
    /// cubic, which always turns the short way.
    quat signed_after(quat prev, quat q) const noexcept { return flips() && dot(prev, q) < 0 ? -q : q; }
    /// The next segment whose keys (and look-ahead) have arrived; with
    /// `end` (no more keys) also the last one. False when there is none.
    /// Throws spline_error for a cubic track whose spline does not converge.
    bool pop(segment& out, bool end);
    /// Forgets the keys: the next one added begins a track (its memory kept).
    void clear() noexcept;

private:
    struct entry {
        double time;
        quat q, s;
        std::array<double, 3> e;
    };
    /// Whether a key's sign is set by the one before it.
    bool flips() const noexcept { return way_ == path::shortest && how_ != method::cubicspline; }
    method how_;
    path way_;
    std::optional<euler_seq> seq_;
    std::vector<entry> window_;  // at most three keys
    // cubicspline: the window's keys as the spline passes them (apart, so
    // that the other methods' entries stay small: reduce builds a segment per probe)
    std::vector<spline_key> splines_;
    bool solve_stretch(bool end);  // cubic: the next stretch's velocities; false if it must wait
    struct {
        std::vector<double> times;  // the keys from `first` on (global indices)
        std::vector<quat> keys;
        std::vector<vec3> phi;       // each key's to the next (rotation_vector_between)
        std::vector<vec3> velocity;  // final before `final`, first guesses after
        std::size_t first = 0, final = 0;
        std::size_t next = 0;  // the segment pop() gives next
        spline_solver solver;
    } cubic_;
};

/// cubic's stretches: keys solved at once, and the keys of look-ahead each leaves to the next.
inline constexpr std::size_t cubic_stretch = 4096, cubic_margin = 256;

/// A whole track's curve, for callers that have all its keys.
class rotation_curve {
public:
    /// Throws option_error for method::euler on a track without a sequence.
    rotation_curve(const track& t, method m, path p);
    /// Key i's rotation, with the sign the path gave it.
    quat at_key(std::size_t i) const noexcept { return keys_[i]; }
    /// The rotation at local parameter h in [0, 1] of segment i (keys i, i+1).
    quat at(std::size_t i, double h) const noexcept { return segments_[i].at(h); }

private:
    std::vector<quat> keys_;
    std::vector<segment_curve> segments_;
};

}  // namespace keyrot
