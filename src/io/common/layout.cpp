// SPDX-License-Identifier: MIT
#include "io/common/layout.hpp"

#include <algorithm>

namespace keyrot {
namespace {

constexpr std::array<std::string_view, 4> quat_wxyz = {"qw", "qx", "qy", "qz"};
constexpr std::array<std::string_view, 4> quat_xyzw = {"qx", "qy", "qz", "qw"};
constexpr std::array<std::string_view, 4> axis_angle_cols = {"ax", "ay", "az", "angle"};
constexpr std::array<std::string_view, 3> rotvec_cols = {"rx", "ry", "rz"};
constexpr std::array<std::string_view, 3> euler_cols = {"e1", "e2", "e3"};
constexpr std::array<std::string_view, 16> matrix4_cols = {"m00", "m01", "m02", "m03", "m10", "m11",
                                                           "m12", "m13", "m20", "m21", "m22", "m23",
                                                           "m30", "m31", "m32", "m33"};
constexpr std::array<std::string_view, 9> matrix_cols = {"m00", "m01", "m02", "m10", "m11",
                                                         "m12", "m20", "m21", "m22"};

}  // namespace

std::string weight_column(std::size_t i) { return "w" + std::to_string(i); }

std::string_view unit_suffix(angle_unit u) noexcept { return u == angle_unit::radians ? "_rad" : ""; }

std::pair<std::string_view, std::optional<angle_unit>> split_unit(std::string_view name) noexcept {
    if (name.ends_with("_rad")) return {name.substr(0, name.size() - 4), angle_unit::radians};
    if (name.ends_with("_deg")) return {name.substr(0, name.size() - 4), angle_unit::degrees};
    return {name, std::nullopt};
}

bool is_angle_column(std::string_view name) noexcept {
    const auto in = [name](const auto& columns) {
        return std::find(columns.begin(), columns.end(), name) != columns.end();
    };
    return name == axis_angle_cols.back() || in(rotvec_cols) || in(euler_cols) || in(velocity_columns) ||
           in(acceleration_columns);
}

std::string column_in(std::string_view name, angle_unit u) {
    std::string out(name);
    if (is_angle_column(name)) out += unit_suffix(u);
    return out;
}

std::span<const std::string_view> rotation_columns(rep r, quat_order order) noexcept {
    switch (r) {
        case rep::quat: return order == quat_order::wxyz ? quat_wxyz : quat_xyzw;
        case rep::axis_angle: return axis_angle_cols;
        case rep::rotvec: return rotvec_cols;
        case rep::euler: return euler_cols;
        case rep::matrix: return matrix_cols;
        case rep::matrix4: return matrix4_cols;
    }
    return {};
}

std::array<double, 4> from_quat_order(std::array<double, 4> v, quat_order order) noexcept {
    if (order == quat_order::wxyz) return v;
    return {v[3], v[0], v[1], v[2]};
}

bool sign_free(const write_options& opts) noexcept {
    switch (opts.representation) {
        case rep::axis_angle:
        case rep::rotvec:
        case rep::matrix:
        case rep::matrix4: return true;
        case rep::quat:
        case rep::euler: return false;
    }
    return false;
}

rotation_values values_of(quat q, const std::optional<vec3>& translation, const write_options& opts) {
    rotation_values out;
    auto put = [&out](double x) { out.v[out.size++] = x; };
    auto angle = [&opts](double radians) { return from_radians(radians, opts.angles); };
    switch (opts.representation) {
        case rep::quat:
            if (opts.order == quat_order::wxyz) put(q.w);
            put(q.x), put(q.y), put(q.z);
            if (opts.order == quat_order::xyzw) put(q.w);
            break;
        case rep::axis_angle: {
            const axis_angle aa = to_axis_angle(q);
            put(aa.axis.x), put(aa.axis.y), put(aa.axis.z), put(angle(aa.angle));
            break;
        }
        case rep::rotvec: {
            // Scale the unit axis by the converted angle rather than
            // converting each component: one rounding fewer.
            const axis_angle aa = to_axis_angle(q);
            const double a = angle(aa.angle);
            put(a * aa.axis.x), put(a * aa.axis.y), put(a * aa.axis.z);
            break;
        }
        case rep::euler: {
            const euler_angles e = to_euler(q, *opts.euler);
            for (double x : e.angles) put(angle(x));
            out.gimbal_lock = e.gimbal_lock;
            break;
        }
        case rep::matrix:
        case rep::matrix4: {
            const mat3 m = to_matrix(q);
            const bool four = opts.representation == rep::matrix4;
            const vec3 t = translation.value_or(vec3{});
            const double column[3] = {t.x, t.y, t.z};
            for (std::size_t r = 0; r < 3; ++r) {
                for (double x : m.m[r]) put(x);
                if (four) put(column[r]);
            }
            if (four) put(0), put(0), put(0), put(1);
            break;
        }
    }
    return out;
}

}  // namespace keyrot
