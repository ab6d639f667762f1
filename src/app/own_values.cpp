// SPDX-License-Identifier: MIT
#include "app/own_values.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "keyrot/interpolate.hpp"
#include "keyrot/tolerances.hpp"

namespace keyrot::detail {

namespace {

/// 1 where `a` is `b` to the bit, -1 where it is -b, else 0.
int same(const quat& a, const quat& b) noexcept {
    if (a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z) return 1;
    if (a.w == -b.w && a.x == -b.x && a.y == -b.y && a.z == -b.z) return -1;
    return 0;
}

/// `x` of unit `from` in unit `to`: as it is where they are one.
double in_unit(double x, angle_unit from, angle_unit to) noexcept {
    return from == to ? x : from_radians(to_radians(x, from), to);
}

/// Whether (x, y, z) is a canonical direction at half a turn: its first
/// non-zero component positive, as to_axis_angle chooses it.
bool canonical_at_half_turn(double x, double y, double z) noexcept {
    return x > 0 || (x == 0 && (y > 0 || (y == 0 && z > 0)));
}

}  // namespace

own_values::own_values(const write_options& w, format out)
    : rep_(out == format::bvh ? rep::euler : w.representation),
      any_(!is_gltf(out) && rep_ != rep::matrix && rep_ != rep::matrix4),
      out_euler_(out == format::bvh ? std::nullopt : w.euler),
      unit_(out == format::bvh ? angle_unit::degrees : w.angles),
      continuous_(out == format::bvh || w.euler_continuous) {}

void own_values::begin_track(const std::optional<euler_seq>& euler, method how, std::optional<double> fps) {
    seq_ = out_euler_ ? out_euler_ : euler;
    own_branch_ = rep_ == rep::euler && euler && seq_ && seq_->name == euler->name;
    how_ = how;
    fps_ = fps;
    keys_.clear(), first_ = 0;
    next_row_ = -std::numeric_limits<double>::infinity();
    previous_.reset();
}

std::optional<given_rotation> own_values::own_of(rep as, const given_rotation& g) const {
    const double half_turn = g.unit == angle_unit::degrees ? 180 : std::numbers::pi, turn = 2 * half_turn;
    given_rotation out = g;
    auto& v = out.values;
    switch (as) {
        case rep::quat:
            if (std::fabs(norm(quat{v[0], v[1], v[2], v[3]}) - 1) > tol::unit_rounding) return std::nullopt;
            return out;
        case rep::axis_angle: {
            // The canonical axis and angle, by steps that round nothing: a negative angle, or one past
            // half a turn, turns the axis round; only the axis's own length is divided out.
            vec3 axis{v[0], v[1], v[2]};
            double angle = v[3];
            if (angle < 0) angle = -angle, axis = -1.0 * axis;
            if (angle > turn || norm(axis) == 0) return std::nullopt;
            if (angle > half_turn) angle = turn - angle, axis = -1.0 * axis;  // (exact: Sterbenz)
            if (angle == 0) return given_rotation{{1, 0, 0, 0}, g.unit};
            if (std::fabs(norm(axis) - 1) > tol::unit_rounding) {
                // Divided in extended precision: each component then the double nearest its exact value.
                const long double x = axis.x, y = axis.y, z = axis.z, n = std::sqrt(x * x + y * y + z * z);
                axis = {static_cast<double>(x / n), static_cast<double>(y / n), static_cast<double>(z / n)};
            }
            if (angle == half_turn && !canonical_at_half_turn(axis.x, axis.y, axis.z)) axis = -1.0 * axis;
            v = {axis.x, axis.y, axis.z, angle};
            return out;
        }
        case rep::rotvec: {
            const double length = norm(vec3{v[0], v[1], v[2]});
            if (length > half_turn) return std::nullopt;
            if (length == half_turn && !canonical_at_half_turn(v[0], v[1], v[2])) v = {-v[0], -v[1], -v[2], 0};
            return out;
        }
        case rep::euler: return own_branch_ ? std::optional(out) : std::nullopt;
        case rep::matrix:
        case rep::matrix4: return std::nullopt;
    }
    return std::nullopt;
}

void own_values::key(const keyrot::key& k) {
    if (!any()) return;
    std::optional<given_rotation> given;
    if (k.given && k.given_as == rep_) given = own_of(k.given_as, *k.given);
    // Euler rows on the keys' own branch start from every key; others look only for keys of their own values.
    if (!given && !own_branch_) return;
    keys_.push_back({k.time, k.rotation, given});
    drop_keys_before(next_row_);
}

void own_values::drop_keys_before(double time) {
    while (held() >= 2 && held_at(1).time <= time) ++first_;
    // (in one move, once they are many: a deque's blocks, made and freed every few keys, cost more)
    if (first_ >= 64 && 2 * first_ >= keys_.size())
        keys_.erase(keys_.begin(), keys_.begin() + static_cast<std::ptrdiff_t>(first_)), first_ = 0;
}

void own_values::put_given(const given_rotation& g, double sign) {
    const auto& v = g.values;
    auto& out = out_.values;
    out_.gimbal_lock = false;
    switch (rep_) {  // (the values canonical as own_of made them)
        case rep::quat: out = {sign * v[0], sign * v[1], sign * v[2], sign * v[3]}; break;
        case rep::axis_angle: out = {v[0], v[1], v[2], in_unit(v[3], g.unit, unit_)}; break;
        default:
            for (std::size_t i = 0; i < 3; ++i) out[i] = in_unit(v[i], g.unit, unit_);
            out[3] = 0;
            break;
    }
}

void own_values::put_angles(const std::array<double, 3>& radians, bool gimbal_lock) {
    for (std::size_t i = 0; i < 3; ++i) out_.values[i] = from_radians(radians[i], unit_);
    out_.values[3] = 0;
    out_.gimbal_lock = gimbal_lock;
}

const own_rotation* own_values::of(double time, const quat& rotation) {
    drop_keys_before(time);
    if (fps_) next_row_ = time + 0.5 / *fps_;  // (the next row is a frame later)
    // The row is a key (at its time, or within the grid's tolerance of the next one).
    const held_key* at = nullptr;
    int sign = 0;
    for (std::size_t i = 0; i < std::min<std::size_t>(held(), 2) && !at; ++i)
        if ((sign = same(held_at(i).rotation, rotation)) != 0) at = &held_at(i);
    if (at && at->given) {
        put_given(*at->given, sign);
        if (rep_ == rep::euler) previous_ = at->given->euler_radians(), previous_from_ = at->time;
        return &out_;
    }
    if (rep_ != rep::euler) return nullptr;
    if (own_branch_ && held() > 0 && held_at(0).given) {
        const held_key& from = held_at(0);
        const given_rotation& a = *from.given;
        if (how_ == method::euler && held() >= 2 && held_at(1).given && time <= held_at(1).time) {
            // The angles the method interpolates, in the keys' own unit where they share one.
            const given_rotation& b = *held_at(1).given;
            const double h = segment_fraction(from.time, held_at(1).time, time);
            std::array<double, 3> radians{};
            const std::array<double, 3> ra = a.euler_radians(), rb = b.euler_radians();
            for (std::size_t i = 0; i < 3; ++i) {
                if (a.unit == b.unit) {
                    const double angle = (1 - h) * a.values[i] + h * b.values[i];
                    out_.values[i] = in_unit(angle, a.unit, unit_);
                    radians[i] = to_radians(angle, a.unit);
                } else {
                    radians[i] = (1 - h) * ra[i] + h * rb[i];
                    out_.values[i] = from_radians(radians[i], unit_);
                }
            }
            out_.values[3] = 0, out_.gimbal_lock = false;
            previous_ = radians, previous_from_ = from.time;
            return &out_;
        }
        // From the row before in this segment, or from the key that begins it.
        const std::array<double, 3> reference = previous_ && previous_from_ == from.time ? *previous_ : a.euler_radians();
        const euler_angles e = continuous_euler(rotation, *seq_, reference);
        put_angles(e.angles, e.gimbal_lock);
        previous_ = e.angles, previous_from_ = from.time;
        return &out_;
    }
    if (!continuous_) return nullptr;
    const euler_angles e = previous_ ? continuous_euler(rotation, *seq_, *previous_) : to_euler(rotation, *seq_);
    put_angles(e.angles, e.gimbal_lock);
    previous_ = e.angles, previous_from_ = std::numeric_limits<double>::quiet_NaN();
    return &out_;
}

}  // namespace keyrot::detail
