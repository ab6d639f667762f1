// SPDX-License-Identifier: MIT
#pragma once
// How rotations are laid out in files, shared by every reader and writer:
// quaternion order, the CSV columns of each representation, the values
// written for a rotation, and how numbers are printed.
#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include "io/common/output.hpp"
#include "keyrot/convert.hpp"
#include "keyrot/names.hpp"
#include "keyrot/quat.hpp"

namespace keyrot {

struct gltf_source;
struct bvh_source;

/// CSV columns of a representation's rotation, in output order:
/// rotation_columns(rep::axis_angle, ...) = {"ax", "ay", "az", "angle"}.
/// For rep::matrix4 these are m00..m33 (translation included).
std::span<const std::string_view> rotation_columns(rep r, quat_order order) noexcept;
inline constexpr std::array<std::string_view, 3> translation_columns = {"tx", "ty", "tz"};
inline constexpr std::array<std::string_view, 3> scale_columns = {"sx", "sy", "sz"};
/// The angular velocity and acceleration (resample --velocity, --acceleration).
inline constexpr std::array<std::string_view, 3> velocity_columns = {"wx", "wy", "wz"};
inline constexpr std::array<std::string_view, 3> acceleration_columns = {"dwx", "dwy", "dwz"};
inline constexpr std::string_view velocity_member = "angular_velocity", acceleration_member = "angular_acceleration";
/// The CSV column of morph weight `i`: "w0", "w1", ...
std::string weight_column(std::size_t i);

/// A column or member that holds angles may say their unit in its name:
/// "angle_rad", "e1_rad", "wx_rad" are radians (per second, for an angular
/// velocity), "angle_deg" degrees. keyrot writes the suffix where its angles
/// are radians, and plain names for degrees, the default.
std::string_view unit_suffix(angle_unit u) noexcept;
/// `name` without its unit suffix, and the unit it states: ("angle",
/// radians) for "angle_rad", (name, none) for a name without one.
std::pair<std::string_view, std::optional<angle_unit>> split_unit(std::string_view name) noexcept;
/// Whether the CSV column `name` (without a unit) holds an angle:
/// axis-angle's angle, the components of a rotation vector, of Euler
/// angles, of an angular velocity and acceleration.
bool is_angle_column(std::string_view name) noexcept;
/// The CSV column `name` as written in angles of `u`: "angle_rad".
std::string column_in(std::string_view name, angle_unit u);

/// Reorder 4 values between file order and (w, x, y, z).
std::array<double, 4> from_quat_order(std::array<double, 4> v, quat_order order) noexcept;

/// Whether a CSV or NDJSON output begins with a line of its settings (a
/// "# keyrot {...}" comment, an NDJSON header object), which other readers
/// of the format take for a row: never by default, since the columns'
/// names say what keyrot needs to read the rows back; always on request
/// (--settings-line). A JSON document always states them, as fields.
enum class settings_line { never, always };
template <>
inline constexpr std::array<enum_name<settings_line>, 2> names_of<settings_line> = {
    {{settings_line::never, "never"}, {settings_line::always, "always"}}};

struct write_options {
    rep representation = rep::axis_angle;
    std::optional<euler_seq> euler;  ///< required for rep::euler
    angle_unit angles = angle_unit::degrees;
    quat_order order = quat_order::wxyz;
    std::optional<int> precision;  ///< digits after the point; none = shortest round trip
    /// glTF output: the glTF input it rewrites (none: a new file).
    std::shared_ptr<gltf_source> gltf = nullptr;
    /// glTF output of a BVH input: its hierarchy, made the nodes.
    std::shared_ptr<bvh_source> bvh = nullptr;
    /// Euler output: each row's angles nearest the row's before (own_values, in app).
    bool euler_continuous = false;
    /// glTF output: LINEAR and STEP rotations as normalised 16-bit integers (--compact).
    bool compact_rotations = false;
    settings_line states = settings_line::never;
    /// How an output file is put in place (--fsync).
    commit_mode commit;
};

/// A rotation's values in column order, angles in the output unit.
struct rotation_values {
    // Only the first `size` are set: one of these is made for every row
    // written, and zeroing all 16 (a microcoded `rep stos`) cost more than
    // filling them.
    std::array<double, 16> v;
    std::size_t size = 0;
    bool gimbal_lock = false;
};
/// `translation` is used by rep::matrix4 only (zero when absent).
rotation_values values_of(quat q, const std::optional<vec3>& translation, const write_options& opts);

/// True where values_of gives q's and -q's values the same bits (q and -q
/// are one rotation): axis-angle, rotation vectors and matrices, which
/// turn w >= 0 exactly or multiply components in pairs. Not quaternions,
/// nor Euler angles (their atan2 of negated pairs may differ in the last bit).
bool sign_free(const write_options& opts) noexcept;

/// Appends v in the shortest form that reads back to the same double, or
/// rounded to `precision` decimals without trailing zeros: append_number(s,
/// 0.1 + 0.2, {}) appends "0.30000000000000004"; (s, 2.50, 3) appends "2.5".
/// Never "-0". Throws std::logic_error for NaN or infinity (a bug, never printed).
void append_number(std::string& out, double v, std::optional<int> precision);

}  // namespace keyrot
