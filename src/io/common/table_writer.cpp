// SPDX-License-Identifier: MIT
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
    rotation_values r;
    if (s.own) {
        const auto& v = s.own->values;
        const rep rep = opts.representation;
        r.size = rep == rep::rotvec || rep == rep::euler ? 3 : 4;
        std::copy_n(v.begin(), r.size, r.v.begin());
        if (rep == rep::quat && opts.order == quat_order::xyzw) r.v = {v[1], v[2], v[3], v[0]};
        r.gimbal_lock = s.own->gimbal_lock;
    } else {
        r = values_of(s.rotation, s.translation, opts);
    }
    if (r.gimbal_lock)
        warn.once("gimbal", fmt::format("gimbal lock in Euler sequence {}: the third angle is set to 0", opts.euler->name));
    return r;
}

std::string settings_members(const table_info& info, const write_options& opts) {
    const rep r = opts.representation;
    std::vector<std::string> members;
    if (info.fps) {
        std::string fps = "\"fps\": ";
        append_number(fps, *info.fps, std::nullopt);
        members.push_back(std::move(fps));
    }
    if (info.method) members.push_back(fmt::format("\"method\": \"{}\"", *info.method));
    members.push_back(fmt::format("\"rep\": \"{}\"", to_string(r)));
    members.push_back(fmt::format("\"angles\": \"{}\"", to_string(opts.angles)));
    if (r == rep::euler) members.push_back(fmt::format("\"euler\": \"{}\"", opts.euler->name));
    if (r == rep::quat) members.push_back(fmt::format("\"quat_order\": \"{}\"", to_string(opts.order)));
    return fmt::format("{}", fmt::join(members, ", "));
}

}  // namespace keyrot
