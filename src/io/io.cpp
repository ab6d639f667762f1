#include "io/io.hpp"

#include <fmt/format.h>


#include "fast/json_stream.hpp"
#include "fast/read_ahead.hpp"
#include "io/io_csv.hpp"
#include "io/io_json.hpp"

namespace keyrot {

void check_track_name(const std::string& name, const std::string& where) {
    if (has_control_characters(name))
        throw input_error(where, fmt::format("track name '{}' has control characters: expected printable text", excerpt(name)));
}

std::unique_ptr<key_reader> make_key_reader(std::istream& in, format f, const read_options& opts, warnings& warn,
                                            std::function<bool()> parse_ahead) {
    std::unique_ptr<line_key_reader> reader = f == format::json     ? make_json_reader(in, opts, warn)
                                              : f == format::ndjson ? make_ndjson_reader(in, opts, warn)
                                                                    : make_csv_reader(in, opts, warn);
    if (parse_ahead) return read_ahead(std::move(reader), std::move(parse_ahead));
    return reader;
}

rotation_values row_values(const sample& s, const write_options& opts, warnings& warn) {
    const rotation_values r = values_of(s.rotation, s.translation, opts);
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

std::unique_ptr<table_writer> make_writer(format f, std::string& out, const table_info& info,
                                          const write_options& opts, warnings& warn) {
    if (f == format::csv) return make_csv_writer(out, info, opts, warn);
    return make_json_writer(out, info, opts, warn, f == format::ndjson);
}

}  // namespace keyrot
