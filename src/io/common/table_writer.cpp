#include "io/common/table_writer.hpp"

#include <fmt/format.h>

#include <iterator>
#include <vector>

#include "io/common/layout.hpp"

namespace keyrot {

vec3 rate_values(vec3 radians, const write_options& opts) {
    return {from_radians(radians.x, opts.angles), from_radians(radians.y, opts.angles), from_radians(radians.z, opts.angles)};
}

rotation_values row_values(const table_row& s, const write_options& opts, warnings& warn) {
    const rotation_values r = values_of(s.rotation, s.translation, opts, s.continuous ? std::optional(s.euler) : std::nullopt);
    if (r.gimbal_lock)
        warn.once("gimbal", fmt::format("gimbal lock in Euler sequence {}: the third angle is set to 0", opts.euler->name));
    return r;
}

std::string settings_members(const table_info& info, const write_options& opts, settings_line which, format f) {
    if (which == settings_line::never) return {};
    const bool all = which == settings_line::always;
    // Rows timed by their frame number alone: CSV writes frames without a
    // time column when every row has a frame and none a time; NDJSON writes
    // each row's own.
    const bool counted = f == format::csv ? info.times == time_columns::as_given && info.all_frames && !info.any_time
                                          : info.counted;
    const rep r = opts.representation;
    // (an angular velocity or acceleration is an angle per second)
    const bool angles = r == rep::axis_angle || r == rep::rotvec || r == rep::euler || info.velocity || info.acceleration;
    const bool arrays = f != format::csv;  // (CSV names its quaternion columns)
    std::vector<std::string> members;
    if (info.fps && (all || (counted && *info.fps != default_key_fps))) {
        std::string fps = "\"fps\": ";
        append_number(fps, *info.fps, std::nullopt);
        members.push_back(std::move(fps));
    }
    if (all && info.method) members.push_back(fmt::format("\"method\": \"{}\"", *info.method));
    if (all) members.push_back(fmt::format("\"rep\": \"{}\"", to_string(r)));
    if (all || (angles && opts.angles != angle_unit::degrees))
        members.push_back(fmt::format("\"angles\": \"{}\"", to_string(opts.angles)));
    if (all && r == rep::euler) members.push_back(fmt::format("\"euler\": \"{}\"", opts.euler->name));
    if (r == rep::quat && (all || (arrays && opts.order != quat_order::wxyz)))
        members.push_back(fmt::format("\"quat_order\": \"{}\"", to_string(opts.order)));
    return fmt::format("{}", fmt::join(members, ", "));
}

}  // namespace keyrot
