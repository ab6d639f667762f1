#include "io/io.hpp"

#include <fmt/format.h>

#include <map>
#include <sstream>

#include "io/io_csv.hpp"
#include "io/io_json.hpp"

namespace keyrot {

void check_track_name(const std::string& name, const std::string& where) {
    if (has_control_characters(name))
        throw input_error(where, fmt::format("track name '{}' has control characters: expected printable text", excerpt(name)));
}

std::unique_ptr<key_reader> make_key_reader(std::istream& in, format f, const read_options& opts, warnings& warn) {
    if (f == format::json) return make_json_reader(in, opts, warn);
    if (f == format::ndjson) return make_ndjson_reader(in, opts, warn);
    return make_csv_reader(in, opts, warn);
}

raw_document read_document(std::istream& in, format f, const read_options& opts, warnings& warn) {
    if (f == format::json) return read_json(in, opts, warn);
    const auto reader = make_key_reader(in, f, opts, warn);
    raw_document doc;
    std::map<std::string, std::size_t> index;
    std::string name;
    raw_key k;
    while (reader->next(name, k)) {
        const auto [it, added] = index.emplace(name, doc.tracks.size());
        if (added) doc.tracks.push_back(raw_track{name, k.at, opts.settings, {}});
        doc.tracks[it->second].keys.push_back(std::move(k));
    }
    doc.named = reader->named();
    if (doc.tracks.empty()) throw input_error(where(opts.source, reader->start()), "no keys: expected at least one key");
    return doc;
}

raw_document read_document(std::string_view text, format f, const read_options& opts, warnings& warn) {
    std::istringstream in{std::string(text)};
    return read_document(in, f, opts, warn);
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
