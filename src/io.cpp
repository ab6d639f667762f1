#include "keyrot/io.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

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
        throw input_error(where, fmt::format("track name '{}' has control characters: expected printable text", name));
}

void track_collector::add(const std::string& name, raw_key k) {
    check_track_name(name, k.where);
    const auto [it, added] = index_.emplace(name, doc_.tracks.size());
    if (added) doc_.tracks.push_back(raw_track{name, k.where, settings_, {}});
    doc_.tracks[it->second].keys.push_back(std::move(k));
}

raw_document read_document(std::string_view text, format f, const read_options& opts, warnings& warn) {
    switch (f) {
        case format::csv: return read_csv(text, opts, warn);
        case format::json: return read_json(text, opts, warn);
        case format::ndjson: return read_ndjson(text, opts, warn);
    }
    return {};
}

rotation_values row_values(const sample& s, const write_options& opts, warnings& warn) {
    const rotation_values r = values_of(s.rotation, s.translation, opts);
    if (r.gimbal_lock)
        warn.once("gimbal", fmt::format("gimbal lock in Euler sequence {}: the third angle is set to 0", opts.euler->name));
    return r;
}

std::unique_ptr<table_writer> make_writer(format f, std::string& out, const table_info& info,
                                          const write_options& opts, warnings& warn) {
    if (f == format::csv) return make_csv_writer(out, info, opts, warn);
    return make_json_writer(out, info, opts, warn, f == format::ndjson);
}

}  // namespace keyrot
