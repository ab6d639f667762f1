#include "keyrot/io.hpp"

#include <fmt/format.h>

#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "keyrot/io_csv.hpp"
#include "keyrot/io_json.hpp"

namespace keyrot {

std::optional<format> parse_format(std::string_view name) {
    if (name == "csv") return format::csv;
    if (name == "json") return format::json;
    if (name == "ndjson") return format::ndjson;
    return std::nullopt;
}

std::string_view to_string(format f) noexcept {
    switch (f) {
        case format::csv: return "csv";
        case format::json: return "json";
        case format::ndjson: return "ndjson";
    }
    return "?";
}

std::optional<format> format_of_path(std::string_view path) {
    const auto dot = path.rfind('.');
    if (dot == std::string_view::npos || path.find('/', dot) != std::string_view::npos) return std::nullopt;
    const std::string ext = ascii_lower(path.substr(dot + 1));
    if (ext == "jsonl") return format::ndjson;
    return parse_format(ext);
}

format sniff_format(std::string_view text) {
    text = without_bom(text);
    const auto start = text.find_first_not_of(" \t\r\n");
    if (start == std::string_view::npos) return format::csv;
    if (text[start] == '[') return format::json;
    if (text[start] != '{') return format::csv;
    // One object per line with more after it is NDJSON; so is a single line
    // holding one key or frame object.
    const auto eol = text.find('\n', start);
    const std::string_view first = text.substr(start, eol == std::string_view::npos ? eol : eol - start);
    const auto j = nlohmann::json::parse(first.begin(), first.end(), nullptr, false);
    if (j.is_discarded() || !j.is_object()) return format::json;
    const bool more = eol != std::string_view::npos && text.find_first_not_of(" \t\r\n", eol) != std::string_view::npos;
    return more || j.contains("time") || j.contains("frame") ? format::ndjson : format::json;
}

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
    if (info.how) fmt::format_to(std::back_inserter(out), "\"method\": \"{}\", ", to_string(*info.how));
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
