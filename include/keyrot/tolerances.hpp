// SPDX-License-Identifier: MIT
#pragma once
// Every tolerance keyrot uses, in one place.
namespace keyrot::tol {

/// |norm - 1| above which a key's quaternion gets the renormalisation warning.
inline constexpr double unit_norm = 1e-3;
/// max |R R^T - I| above which a matrix is not a rotation.
inline constexpr double orthonormal = 1e-3;
/// Output frames within this many frames of the key range are on the grid.
inline constexpr double grid_frames = 1e-9;
/// Middle Euler angle (radians) this close to 0 or pi counts as gimbal lock.
/// Setting the third angle to 0 there moves the rotation by at most about
/// this much, so it is kept at the size of a rounding error.
inline constexpr double gimbal_lock = 4e-16;
/// Keys q0, q1 with q0^-1 q1 = (w < 0, v) and |v| below this are opposite:
/// slerp between them (--path direct) is a full turn about q0's local x.
/// The compensated product fixes v only to about 1e-32, so below this the
/// direction of v, the axis of the turn, would be rounding noise.
inline constexpr double opposite_keys = 1e-15;
/// A quaternion or an axis given this close to unit length is one but for
/// its digits' rounding (two units in the last place): a round trip writes
/// it back as given, where a longer one is normalised.
inline constexpr double unit_rounding = 4e-16;
/// |dt| in seconds under which compare matches rows by time.
inline constexpr double match_time = 1e-6;

}  // namespace keyrot::tol
