// SPDX-License-Identifier: MIT
#pragma once
// The members of a JSON or NDJSON key object, named once for the readers
// (what they look for, and what is unknown), the writer and `keyrot help
// formats`.
#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <string_view>

#include "io/common/layout.hpp"
#include "keyrot/convert.hpp"

namespace keyrot {

/// The member that holds a rotation of representation `r`: "axis" for
/// axis-angle (its angle in angle_member), "matrix" for both matrices.
constexpr std::string_view rotation_member(rep r) noexcept {
    switch (r) {
        case rep::quat: return "quat";
        case rep::axis_angle: return "axis";
        case rep::rotvec: return "rotvec";
        case rep::euler: return "euler";
        case rep::matrix:
        case rep::matrix4: return "matrix";
    }
    return "";
}
/// Axis-angle's angle, beside its axis.
inline constexpr std::string_view angle_member = "angle";
/// Whether a key's member holds angles, whose unit its name may say ("euler_rad").
constexpr bool is_angle_member(std::string_view name) noexcept {
    return name == angle_member || name == rotation_member(rep::rotvec) || name == rotation_member(rep::euler) ||
           name == velocity_member || name == acceleration_member;
}
/// The quaternion's member where its array's order is named: "quat_xyzw".
inline constexpr std::string_view quat_xyzw_member = "quat_xyzw", quat_wxyz_member = "quat_wxyz";
/// Member `name` as an NDJSON line writes it in angles of `u` and quaternion order `o`: with the unit
/// or order where not the default ("angle_rad", "quat_xyzw"), as a JSON document states them in its fields.
inline std::string member_in(std::string_view name, angle_unit u, quat_order o) {
    if (name == rotation_member(rep::quat)) return std::string(o == quat_order::xyzw ? quat_xyzw_member : name);
    std::string out(name);
    if (is_angle_member(name)) out += unit_suffix(u);
    return out;
}
/// A key's time: seconds ("time", or "t" in slerp's tables) or a frame.
inline constexpr std::array<std::string_view, 3> time_members = {"time", "t", "frame"};

namespace detail {
template <std::size_t... N>
constexpr auto joined(const std::array<std::string_view, N>&... parts) {
    std::array<std::string_view, (N + ...)> out{};
    std::size_t at = 0;
    ((std::copy(parts.begin(), parts.end(), out.begin() + static_cast<std::ptrdiff_t>(at)), at += N), ...);
    return out;
}
}  // namespace detail

/// The rotation members, each once.
inline constexpr std::array<std::string_view, 5> rotation_members = {
    rotation_member(rep::quat), rotation_member(rep::axis_angle), rotation_member(rep::rotvec),
    rotation_member(rep::euler), rotation_member(rep::matrix)};
/// Every member a key object may hold: any other is unknown (a warning,
/// an error with --strict).
inline constexpr auto key_members =
    detail::joined(time_members, rotation_members,
                   std::array<std::string_view, 7>{angle_member, "translation", "scale", "track", "weights",
                                                   velocity_member, acceleration_member});

}  // namespace keyrot
