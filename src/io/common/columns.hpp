// SPDX-License-Identifier: MIT
#pragma once
// A table's columns by name, and a row's cells into a key by them: a CSV
// header and its rows, and a JSON record of the same names (the rows of a
// table as Miller and pandas write them), read alike.
#include <fmt/format.h>

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "io/common/layout.hpp"
#include "io/common/raw_key.hpp"

namespace keyrot {

/// Where each column keyrot reads is, resolved once from the names.
struct column_layout {
    std::size_t count = 0;
    std::optional<std::size_t> track, time, frame;
    rep kind = rep::quat;
    std::vector<std::size_t> rotation;  // in rotation_columns(kind, wxyz) order: (w, x, y, z) for quaternions
    std::optional<std::array<std::size_t, 3>> translation, scale;
    std::vector<std::size_t> weights;  // w0, w1, ...
    std::optional<std::array<std::size_t, 3>> velocity, acceleration;
    /// The unit the angle columns' names state ("angle_rad"), if any.
    std::optional<angle_unit> angles;
    std::vector<bool> known;  // per column: one keyrot reads
};

/// The layout of columns named `names` (as written: case and spaces around
/// do not count; an empty name is no column, as the index pandas writes
/// first). Throws input_error at `where` for names that hold no keys: no
/// time, a name twice, two representations' columns or one's in part, a
/// translation's in part, units that disagree.
column_layout layout_of(std::span<const std::string_view> names, const std::string& where);

/// Whether `name` (in lower case) is a column of a rotation, so that an
/// object that has one is a table's row.
bool is_rotation_column(std::string_view name);

/// Fills `k` from the cells of one row laid out as `cols`. `Cells` gives
/// `bool empty(i)`, `double number(i, name)` (throwing input_error for
/// what is not a number) and `std::string text(i)` (the track's cell), and
/// `fail(message)` (throwing input_error for the row).
template <class Cells>
void read_row(const column_layout& cols, Cells& cells, std::string& track, raw_key& k);

template <class Cells>
void read_row(const column_layout& cols, Cells& cells, std::string& track, raw_key& k) {
    if (cols.time && !(cols.frame && cells.empty(*cols.time))) k.time = cells.number(*cols.time, "time");
    if (cols.frame && !(cols.time && cells.empty(*cols.frame))) k.frame = cells.number(*cols.frame, "frame");
    if (!k.time && !k.frame) cells.fail("no time: expected a 'time' or a 'frame'");
    k.kind = cols.kind;
    const auto names = rotation_columns(cols.kind, quat_order::wxyz);
    for (std::size_t i = 0; i < cols.rotation.size(); ++i) k.values[i] = cells.number(cols.rotation[i], names[i]);
    const auto vector = [&](const std::optional<std::array<std::size_t, 3>>& at, const auto& column) {
        std::optional<vec3> v;
        if (!at) return v;
        const auto& c = *at;
        const int empty = cells.empty(c[0]) + cells.empty(c[1]) + cells.empty(c[2]);
        if (empty == 0) v = vec3{cells.number(c[0], column[0]), cells.number(c[1], column[1]), cells.number(c[2], column[2])};
        else if (empty != 3)
            cells.fail(fmt::format("columns {}: expected three numbers or three empty cells", fmt::join(column, " ")));
        return v;
    };
    k.translation = vector(cols.translation, translation_columns);
    k.scale = vector(cols.scale, scale_columns);
    k.rates = {vector(cols.velocity, velocity_columns), vector(cols.acceleration, acceleration_columns)};
    // A track with fewer morph targets than the table's columns leaves the last of them empty.
    for (std::size_t i = 0; i < cols.weights.size(); ++i) {
        if (cells.empty(cols.weights[i])) continue;
        if (k.weights.size() != i)
            cells.fail(fmt::format("column '{}' after an empty '{}': expected the weights as numbers from w0 on, and "
                                   "the columns after them empty",
                                   weight_column(i), weight_column(k.weights.size())));
        k.weights.push_back(cells.number(cols.weights[i], weight_column(i)));
    }
    k.angles = cols.angles;
    track.clear();
    if (cols.track) {
        track = cells.text(*cols.track);
        if (track.empty()) cells.fail("column 'track': expected a track name, got an empty cell");
    }
}

}  // namespace keyrot
