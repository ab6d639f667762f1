// SPDX-License-Identifier: MIT
#pragma once
// What a round trip gives back: each row's rotation values where they are
// the input's own, or follow the input's own Euler branch.
#include <array>
#include <optional>
#include <vector>

#include "io/common/format.hpp"
#include "io/common/interface.hpp"
#include "keyrot/method.hpp"

namespace keyrot::detail {

/// The values a row writes (table_row::own), where the writer's own
/// working out would not give the user's numbers back. A key given in the
/// output's representation comes back with the numbers it was given, made
/// canonical where they are not only by steps that round nothing (a
/// quaternion of unit length but for its digits' rounding; an axis and
/// angle, the angle within a turn, the axis divided by its length where
/// that is not 1; a rotation vector up to half a turn long; Euler angles in
/// the output's sequence, on whatever branch). Between Euler keys in the output's sequence, a row's angles
/// continue from the row before in the same segment, starting from the key
/// that begins it, so a one-frame flip disturbs only its own segments
/// (linear in the keys' own angles for --method euler). With
/// --euler-continuous, and in BVH, every Euler row continues from the one
/// before. Rows come in time order within a track, each after the keys
/// that make it (key()).
class own_values {
public:
    /// For an output of format `out` written with `w`: BVH in each track's
    /// own Euler sequence, in degrees, continuous; glTF never (it stores
    /// quaternions).
    own_values(const write_options& w, format out);

    /// Whether a row may have values of its own (else nothing need be told).
    bool any() const noexcept { return any_; }
    /// A track begins: its keys in sequence `euler` (if any), interpolated
    /// by `how`; its rows on the grid of `fps` (resample), or its keys.
    void begin_track(const std::optional<euler_seq>& euler, method how, std::optional<double> fps);
    /// The next key of the track, before the rows it takes part in.
    void key(const key& k);
    /// The values of the track's next row, at `time` with `rotation`;
    /// none where the writer is to work them out. Valid until the next call.
    const own_rotation* of(double time, const quat& rotation);

private:
    struct held_key {
        double time;
        quat rotation;
        std::optional<given_rotation> given;  // own_of its values, where it has some
    };
    std::size_t held() const noexcept { return keys_.size() - first_; }
    const held_key& held_at(std::size_t i) const noexcept { return keys_[first_ + i]; }
    /// Lets go of the keys before the last at or before `time`.
    void drop_keys_before(double time);
    /// Values in the output of a key's given values `g`, `sign` -1 for a row at -q.
    void put_given(const given_rotation& g, double sign);
    /// Euler angles (radians) into the output, its unit.
    void put_angles(const std::array<double, 3>& radians, bool gimbal_lock);
    /// The values the output writes of given values `g` of kind `as`,
    /// where they are the given numbers (turned canonical only by steps
    /// that round nothing); none where the writer's are to be written.
    std::optional<given_rotation> own_of(rep as, const given_rotation& g) const;

    rep rep_;
    bool any_;
    std::optional<euler_seq> out_euler_;  // none in BVH: each track's own
    angle_unit unit_;
    bool continuous_;
    // the track's
    std::optional<euler_seq> seq_;  // the output's sequence
    bool own_branch_ = false;       // Euler output in the keys' own sequence
    method how_ = method::slerp;
    std::optional<double> fps_;
    std::vector<held_key> keys_;  // from first_, the last at or before the next row, on
    std::size_t first_ = 0;
    double next_row_ = 0;        // no row is before it (with fps_)
    std::optional<std::array<double, 3>> previous_;  // the last row's angles (radians)
    double previous_from_ = 0;                       // the time of the key whose segment it was in
    own_rotation out_;
};

}  // namespace keyrot::detail
