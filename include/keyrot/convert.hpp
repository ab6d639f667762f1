// SPDX-License-Identifier: MIT
#pragma once
// Conversions between unit quaternions and the other rotation representations.
// Every angle here is in radians; units are the readers' and writers' business.
#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "keyrot/names.hpp"
#include "keyrot/quat.hpp"

namespace keyrot {

/// The rotation representations of the spec, as named on the command line.
enum class rep { quat, axis_angle, rotvec, euler, matrix, matrix4 };
template <>
inline constexpr std::array<enum_name<rep>, 6> names_of<rep> = {{{rep::axis_angle, "axis-angle"},
                                                             {rep::quat, "quat"},
                                                             {rep::rotvec, "rotvec"},
                                                             {rep::euler, "euler"},
                                                             {rep::matrix, "matrix"},
                                                             {rep::matrix4, "matrix4"}}};

/// The order of a quaternion's four numbers in a file.
enum class quat_order { wxyz, xyzw };
template <>
inline constexpr std::array<enum_name<quat_order>, 2> names_of<quat_order> = {
    {{quat_order::wxyz, "wxyz"}, {quat_order::xyzw, "xyzw"}}};

enum class angle_unit { degrees, radians };
template <>
inline constexpr std::array<enum_name<angle_unit>, 2> names_of<angle_unit> = {
    {{angle_unit::degrees, "degrees"}, {angle_unit::radians, "radians"}}};
/// Unit conversions, rounded once (to within half an ulp).
double to_radians(double angle, angle_unit from) noexcept;
/// to_radians(90, angle_unit::degrees) = pi/2; from_radians(pi, angle_unit::degrees) = 180.
double from_radians(double radians, angle_unit to) noexcept;

/// An Euler sequence in scipy's naming: "XYZ" intrinsic, "zyx" extrinsic.
struct euler_seq {
    std::array<int, 3> axes{};  ///< 0 = x, 1 = y, 2 = z, in the order written
    bool intrinsic = false;
    std::string name;
};
/// "ZYX" -> intrinsic z, y, x. std::nullopt unless three letters from xyz,
/// all the same case, no two consecutive letters equal.
std::optional<euler_seq> parse_euler_seq(std::string_view name);

struct axis_angle {
    vec3 axis{1, 0, 0};  ///< unit
    double angle = 0;    ///< radians
};

// The from_ functions take their angles in `unit`; degrees are reduced by
// whole quarter turns before any rounding, so 90, 180 and 360 are exact.

/// Precondition: axis non-zero and finite (it need not be unit).
/// from_axis_angle({0, 0, 2}, pi/2) = (cos 45deg, 0, 0, sin 45deg).
quat from_axis_angle(vec3 axis, double angle, angle_unit unit = angle_unit::radians) noexcept;
/// Rotation vector = unit axis * angle; the zero vector is the identity.
quat from_rotvec(vec3 rotvec, angle_unit unit = angle_unit::radians) noexcept;
/// Angles in the order of the sequence. from_euler({a, b, c}, "XYZ") = Rx(a) Ry(b) Rz(c).
quat from_euler(std::array<double, 3> angles, const euler_seq& seq,
                angle_unit unit = angle_unit::radians) noexcept;
/// Precondition: m is a rotation matrix to within the reader's tolerance.
/// Picks the best-conditioned of the four Shepperd branches, as scipy does.
quat from_matrix(const mat3& m) noexcept;

/// Angle in [0, pi]. The identity gives axis (1, 0, 0), angle 0. At exactly
/// 180 degrees (w = 0) q and -q are both valid; the axis is chosen with its
/// first non-zero component positive, so the answer does not depend on sign.
axis_angle to_axis_angle(quat q) noexcept;
/// The unit axis times the angle in [0, pi]: to_rotvec(90 degrees about z) = {0, 0, pi/2}.
vec3 to_rotvec(quat q) noexcept;

struct euler_angles {
    std::array<double, 3> angles{};  ///< scipy's canonical ranges
    bool gimbal_lock = false;        ///< third angle was set to 0
};
/// Direct quaternion-to-Euler (Bernardes & Viollet 2022), as scipy >= 1.11.
euler_angles to_euler(quat q, const euler_seq& seq) noexcept;
/// The angles of `q` in `seq` nearest `previous` (radians), for curves that
/// never jump by a turn or flip at +-180 degrees: of the two solutions
/// (a, b, c) and (a + pi, pi - b, c + pi) (-b for proper Euler sequences),
/// each angle moved by whole turns to within half a turn of the previous
/// one, the one whose angles move least in all (gimbal_lock as to_euler's).
euler_angles continuous_euler(quat q, const euler_seq& seq, const std::array<double, 3>& previous) noexcept;
/// The rotation matrix acting on column vectors: to_matrix(90 degrees about z).m[0] = {0, -1, 0}.
mat3 to_matrix(quat q) noexcept;

}  // namespace keyrot
