#pragma once
// Interpolation methods: the kernels (slerp, nlerp, squad) and the curve
// through a track's keys that resample evaluates segment by segment.
#include <array>
#include <optional>
#include <string_view>
#include <vector>

#include "keyrot/quat.hpp"
#include "keyrot/track.hpp"

namespace keyrot {

enum class method { slerp, nlerp, squad, step, euler };
enum class path { shortest, direct };

inline constexpr std::array<std::string_view, 5> method_names = {"slerp", "nlerp", "squad", "step", "euler"};
inline constexpr std::array<std::string_view, 2> path_names = {"shortest", "direct"};
std::optional<method> parse_method(std::string_view name);
std::string_view to_string(method m) noexcept;
std::optional<path> parse_path(std::string_view name);
std::string_view to_string(path p) noexcept;

/// Spherical linear interpolation from a to b, prepared once per pair of
/// keys: Szeliski's Algorithm 2.1 with the relative rotation's axis and
/// angle lifted out of the per-frame loop, the angle kept to twice the
/// working precision so that the result is within about 2x of correctly
/// rounded even on the long way round.
class slerp_segment {
public:
    slerp_segment(quat a, quat b) noexcept;
    /// Constant angular speed, no sign flip (a and b as given, so b = -a
    /// turns a full 360 degrees, about a's local x). Exact at h = 0 and 1.
    quat at(double h) const noexcept;

private:
    quat a_, b_;
    long double axis_x_ = 1, axis_y_ = 0, axis_z_ = 0;  // of conjugate(a) * b
    double half_ = 0, half_lo_ = 0;                     // its half angle, as hi + lo
};

/// slerp_segment(a, b).at(h). slerp(1, 90deg@z, 0.5) = 45deg@z.
quat slerp(quat a, quat b, double h) noexcept;
/// Lerp of the components, normalised (seed 000, "method 1"). If the lerp
/// is zero (b = -a, h = 1/2) the rotation is a's.
quat nlerp(quat a, quat b, double h) noexcept;
/// Shoemake's control point s_i = q_i exp(-(log(q_i^-1 q_next) + log(q_i^-1 q_prev)) / 4).
quat squad_control(quat prev, quat cur, quat next) noexcept;
/// slerp(slerp(q0, q1, h), slerp(s0, s1, h), 2h(1 - h)); no sign flips.
quat squad(quat q0, quat q1, quat s0, quat s1, double h) noexcept;

/// The rotation curve through one track's keys for one method and path.
/// Precondition: the track passed make_track's validation.
class rotation_curve {
public:
    /// Throws usage_error for --method euler on a track without a sequence.
    rotation_curve(const track& t, method m, path p);
    /// Key i's rotation, with the sign the path gave it.
    quat at_key(std::size_t i) const noexcept { return q_[i]; }
    /// The rotation at local parameter h in [0, 1] of segment i (keys i, i+1).
    quat at(std::size_t i, double h) const noexcept;

private:
    method method_;
    std::optional<euler_seq> seq_;
    std::vector<quat> q_;                        // keys, hemisphere-aligned for --path shortest
    std::vector<slerp_segment> slerps_;          // slerp: q_i to q_i+1; squad: that, then s_i to s_i+1
    std::vector<quat> s_;                        // squad control points
    std::vector<std::array<double, 3>> euler_;  // Euler angles per key, for --method euler
};

/// The translation channel: linear between the keys that carry one (held
/// for step), held before the first and after the last of them.
class translation_curve {
public:
    translation_curve(const track& t, method m);
    /// std::nullopt when no key has a translation. Times within `tol`
    /// seconds of a translation key give that key's value exactly.
    std::optional<vec3> at(double time, double tol) const noexcept;

private:
    bool hold_;
    std::vector<double> times_;
    std::vector<vec3> values_;
};

}  // namespace keyrot
