// SPDX-License-Identifier: MIT
#include "formats_help.hpp"

#include <fmt/format.h>

#include <array>
#include <string_view>

#include "io/common/layout.hpp"
#include "io/json/json_members.hpp"

namespace keyrot {
namespace {

/// Each representation's value in a JSON key object, under its member
/// (io/json/json_members.hpp, the names the readers and writer use; the CSV
/// columns come from io/common/layout).
constexpr std::array<std::pair<rep, std::string_view>, 6> json_values = {{
    {rep::axis_angle, "[x, y, z]"},
    {rep::quat, R"([w, x, y, z] in the quat_order, or {"w": w, "x": x, "y": y, "z": z})"},
    {rep::rotvec, "[x, y, z]"},
    {rep::euler, "[e1, e2, e3], in the order of the sequence"},
    {rep::matrix, "[[m00, m01, m02], [m10, m11, m12], [m20, m21, m22]]"},
    {rep::matrix4, "four rows of four, translation in the last column"},
}};

std::string columns(rep r, quat_order order) { return fmt::format("{}", fmt::join(rotation_columns(r, order), ",")); }

/// Axis-angle's angle column, the one whose unit the help shows.
const std::string_view axis_angle_angle = rotation_columns(rep::axis_angle, quat_order::wxyz).back();

}  // namespace

std::string formats_help() {
    std::string out = "CSV: a header line of column names (any case, any order), then one key per line; blank lines\n"
                      "and lines starting with '#' are skipped. The rotation's columns, by representation (--rep):\n";
    for (const auto& [r, name] : names_of<rep>) {
        out += fmt::format("  {:<12}{}", name, columns(r, quat_order::wxyz));
        if (r == rep::quat) out += fmt::format("  (--quat-order xyzw: {})", columns(r, quat_order::xyzw));
        if (r == rep::euler) out += "  (angles in the order of --euler's sequence)";
        out += '\n';
    }
    out += fmt::format("Beside them: time or frame (at --key-fps, default 24; keyrot writes time, and frame beside\n"
                       "it where there are frames); track (optional, names the track); {} (optional translation);\n"
                       "{} (optional scale); w0,w1,... (optional morph weights, as many on every key of a track);\n"
                       "{} and {} (angular velocity and acceleration). A column of angles may say\n"
                       "their unit: {} is radians (keyrot writes them so), angle_deg degrees.\n",
                       fmt::join(translation_columns, ","), fmt::join(scale_columns, ","), fmt::join(velocity_columns, ","),
                       fmt::join(acceleration_columns, ","), column_in(axis_angle_angle, angle_unit::radians));
    out += "\nJSON: a document {\"keys\": [KEY, ...]}, a bare array [KEY, ...], or {\"tracks\": {\"NAME\": {\"keys\": [...]}, "
           "...}}.\nOptional document (or track) fields: \"angles\": \"degrees\" | \"radians\", \"euler\": \"ZYX\", "
           "\"quat_order\":\n\"wxyz\" | \"xyzw\", \"fps\" (the rate of \"frame\"). A KEY holds \"time\" or \"frame\", "
           "one rotation, and optionally\n\"translation\": [x, y, z], \"scale\": [x, y, z] and \"weights\": [w0, w1, ...]. "
           "The rotation's fields,\nby representation:\n";
    for (const auto& [r, value] : json_values) {
        out += fmt::format("  {:<12}\"{}\": {}", to_string(r), rotation_member(r), value);
        if (r == rep::axis_angle) out += fmt::format(", \"{}\": a", angle_member);
        out += '\n';
    }
    out += fmt::format("\nNDJSON: one KEY object per line, with \"track\" when there are tracks; a member may say its\n"
                       "unit or order, as keyrot writes them where not the default: \"{}\", \"{}\" (and the\n"
                       "other angles'), \"{}\". A first line without a rotation holds the settings\n"
                       "(--settings-line always writes one). A JSON or NDJSON object of CSV column names\n"
                       "({{\"time\": 0, \"qw\": 1, ...}}, a table's rows as Miller and pandas write them) is read as that\n"
                       "CSV row.\n",
                       member_in(angle_member, angle_unit::radians, quat_order::wxyz),
                       member_in(rotation_member(rep::euler), angle_unit::radians, quat_order::wxyz),
                       member_in(rotation_member(rep::quat), angle_unit::degrees, quat_order::xyzw));
    out += "\nglTF 2.0 (.gltf with its buffers, or .glb): each node an animation moves is a track named after it\n"
           "(\"<animation>/<node>\" when there are several animations; --animation picks one), its rotation,\n"
           "translation, scale and morph weights channels interpolated as their samplers say (LINEAR, STEP,\n"
           "CUBICSPLINE). A glTF output of a glTF input is that file with its samplers replaced; of any other\n"
           "input, a new file with a node per track (and no morph weights, which need the input's mesh).\n"
           "\nBVH (.bvh): each joint with channels is a track named after it, its rotation channels the intrinsic\n"
           "Euler sequence of their order (Zrotation Xrotation Yrotation: ZXY, in degrees), its position channels\n"
           "the translation; frame f at f / rate. A BVH output needs a BVH input, whose hierarchy it keeps; at\n"
           "the input's frames its values are the input's own, and between them continuous.\n"
           "\nA file's format is known by its extension (.csv, .json, .ndjson or .jsonl, .gltf, .glb, .bvh), else by\n"
           "its content.\n"
           "keyrot reads all it writes: a JSON document with \"frames\" in place of \"keys\", and a CSV file's "
           "first line\n\"# keyrot {...}\" of its settings (--settings-line always).\n";
    return out;
}

}  // namespace keyrot
