// SPDX-License-Identifier: MIT
#include "io/common/columns.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "ground/text.hpp"

namespace keyrot {
namespace {

constexpr std::array<std::string_view, 7> matrix4_only = {"m03", "m13", "m23", "m30", "m31", "m32", "m33"};

std::string column_list(rep r) {
    const auto cols = rotation_columns(r, quat_order::wxyz);
    if (r == rep::matrix || r == rep::matrix4) return fmt::format("{}..{}", cols.front(), cols.back());
    return fmt::format("{}", fmt::join(cols, " "));
}

}  // namespace

bool is_rotation_column(std::string_view name) {
    const std::string_view base = split_unit(name).first;
    for (const auto& r : names_of<rep>) {
        const auto cols = rotation_columns(r.value, quat_order::wxyz);
        if (std::find(cols.begin(), cols.end(), base) != cols.end()) return true;
    }
    return false;
}

column_layout layout_of(std::span<const std::string_view> names, const std::string& where) {
    column_layout cols;
    cols.count = names.size();
    cols.known.assign(names.size(), false);
    std::map<std::string, std::size_t, std::less<>> index;  // an angle's column by its name without the unit
    std::vector<std::string> lower(names.size());
    std::vector<std::optional<angle_unit>> unit_of(names.size());  // what an angle column's name states
    for (std::size_t i = 0; i < names.size(); ++i) {
        const std::string name = lower[i] = ascii_lower(trim(names[i]));
        if (name.empty()) continue;  // pandas' to_csv writes its index so; ignored as unknown columns are
        const auto [base, unit] = split_unit(name);
        const bool angle = unit && is_angle_column(base);
        if (angle) unit_of[i] = unit;
        if (!index.emplace(angle ? std::string(base) : name, i).second)
            throw input_error(where, fmt::format("column '{}' appears twice: expected each column once",
                                                 angle ? std::string(base) : name));
    }
    auto find = [&index](std::string_view name) -> std::optional<std::size_t> {
        const auto it = index.find(name);
        if (it == index.end()) return std::nullopt;
        return it->second;
    };
    auto claim = [&](std::string_view name) {
        auto at = find(name);
        if (at) cols.known[*at] = true;
        return at;
    };
    cols.track = claim("track");
    cols.time = claim("time");
    if (!cols.time) cols.time = claim("t");  // slerp's tables
    cols.frame = claim("frame");
    if (!cols.time && !cols.frame) throw input_error(where, "no time column: expected a 'time' or 'frame' column");

    // The representation: the one whose columns appear. The 3x3 matrix
    // columns are also part of the 4x4 ones, so matrix4 is chosen by the
    // columns only it has.
    const bool four = std::any_of(matrix4_only.begin(), matrix4_only.end(), [&](auto n) { return find(n).has_value(); });
    std::optional<rep> found;
    for (rep r : {rep::quat, rep::axis_angle, rep::rotvec, rep::euler, four ? rep::matrix4 : rep::matrix}) {
        const auto rotation = rotation_columns(r, quat_order::wxyz);
        if (std::none_of(rotation.begin(), rotation.end(), [&](auto n) { return find(n).has_value(); })) continue;
        if (found)
            throw input_error(where, fmt::format("columns of two rotation representations ({} and {}): expected one",
                                                 to_string(*found), to_string(r)));
        for (auto n : rotation)
            if (!find(n))
                throw input_error(where, fmt::format("missing column '{}': {} needs {}", n, to_string(r), column_list(r)));
        found = r;
        for (auto n : rotation) cols.rotation.push_back(*claim(n));
    }
    if (!found)
        throw input_error(where, fmt::format("no rotation columns: expected {}, {}, {}, {} or {}", column_list(rep::quat),
                                             column_list(rep::axis_angle), column_list(rep::rotvec),
                                             column_list(rep::euler), column_list(rep::matrix)));
    cols.kind = *found;

    const auto vector_columns = [&](const auto& vector, std::string_view what) {
        std::optional<std::array<std::size_t, 3>> at;
        const auto x = claim(vector[0]), y = claim(vector[1]), z = claim(vector[2]);
        if (!x && !y && !z) return at;
        if (!(x && y && z))
            throw input_error(where, fmt::format("{} needs all of the columns {}", what, fmt::join(vector, " ")));
        return at = std::array<std::size_t, 3>{*x, *y, *z};
    };
    cols.translation = vector_columns(translation_columns, "translation");
    if (cols.translation && cols.kind == rep::matrix4)
        throw input_error(where, "4x4 matrix and tx ty tz columns: expected one translation per key");
    cols.scale = vector_columns(scale_columns, "scale");
    cols.velocity = vector_columns(velocity_columns, "angular velocity");
    cols.acceleration = vector_columns(acceleration_columns, "angular acceleration");
    for (std::size_t n = 0; n < index.size(); ++n) {  // w0 ... wN-1, one after another
        const auto at = claim(weight_column(n));
        if (!at) break;
        cols.weights.push_back(*at);
    }
    // The angles' unit: stated by every angle column read, or by none (the flags' then).
    std::optional<std::size_t> stating, plain;
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (!cols.known[i] || !is_angle_column(split_unit(lower[i]).first)) continue;
        if (!unit_of[i]) {
            if (!plain) plain = i;
        } else if (!stating) {
            stating = i;
        } else if (unit_of[i] != unit_of[*stating]) {
            throw input_error(where, fmt::format("columns '{}' and '{}' state two angle units: expected one",
                                                 lower[*stating], lower[i]));
        }
    }
    if (stating && plain)
        throw input_error(where, fmt::format("column '{}' states its angle unit and '{}' does not: expected every angle "
                                             "column with its unit, or none",
                                             lower[*stating], lower[*plain]));
    if (stating) cols.angles = unit_of[*stating];
    for (const auto& [name, at] : index)
        if (!cols.known[at] && name.size() > 1 && name[0] == 'w' &&
            name.find_first_not_of("0123456789", 1) == std::string::npos)
            throw input_error(where, fmt::format("column '{}' without '{}': expected the morph weights' columns w0 to "
                                                 "wN-1, each once",
                                                 name, weight_column(cols.weights.size())));
    return cols;
}

}  // namespace keyrot
