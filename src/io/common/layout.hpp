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

/// Reorder 4 values between file order and (w, x, y, z).
std::array<double, 4> from_quat_order(std::array<double, 4> v, quat_order order) noexcept;

/// When a CSV or NDJSON output states its settings in a line of their own
/// (a leading "# keyrot {...}" comment, an NDJSON header object), which
/// other readers of the format take for a row: when keyrot, reading the
/// output back with no flags, would otherwise misread it (needed), always,
/// or never (--settings-line). A JSON document always states them, as
/// fields.
enum class settings_line { needed, always, never };
template <>
inline constexpr std::array<enum_name<settings_line>, 3> names_of<settings_line> = {
    {{settings_line::needed, "needed"}, {settings_line::always, "always"}, {settings_line::never, "never"}}};

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
    /// Euler output: each row's angles nearest the row's before (continuous_euler).
    bool euler_continuous = false;
    /// glTF output: LINEAR and STEP rotations as normalised 16-bit integers (--compact).
    bool compact_rotations = false;
    settings_line states = settings_line::needed;
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
/// `translation` is used by rep::matrix4 only (zero when absent); `euler`
/// (radians), by rep::euler in place of the canonical angles of `q`.
rotation_values values_of(quat q, const std::optional<vec3>& translation, const write_options& opts,
                          const std::optional<std::array<double, 3>>& euler = std::nullopt);

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
