#include "io/table_writer.hpp"

#include <fmt/format.h>

#include <iterator>

#include "io/layout.hpp"

namespace keyrot {

rotation_values row_values(const sample& s, const write_options& opts, warnings& warn) {
    const rotation_values r = values_of(s.rotation, s.translation, opts, s.euler);
    if (r.gimbal_lock)
        warn.once("gimbal", fmt::format("gimbal lock in Euler sequence {}: the third angle is set to 0", opts.euler->name));
    return r;
}

std::string settings_members(const table_info& info, const write_options& opts) {
    std::string out;
    if (info.fps) out += "\"fps\": ", append_number(out, *info.fps, std::nullopt), out += ", ";
    if (info.method) fmt::format_to(std::back_inserter(out), "\"method\": \"{}\", ", *info.method);
    fmt::format_to(std::back_inserter(out), "\"rep\": \"{}\", \"angles\": \"{}\"", to_string(opts.representation),
                   to_string(opts.angles));
    if (opts.representation == rep::euler) fmt::format_to(std::back_inserter(out), ", \"euler\": \"{}\"", opts.euler->name);
    if (opts.representation == rep::quat)
        fmt::format_to(std::back_inserter(out), ", \"quat_order\": \"{}\"", to_string(opts.order));
    return out;
}

}  // namespace keyrot
