// SPDX-License-Identifier: MIT
#pragma once
// What the reader and writer tests share: an input read as the commands
// read it (io/document.hpp), its first error, a table written.
#include <memory>
#include <sstream>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io/common/interface.hpp"
#include "io/common/table_writer.hpp"
#include "io/csv/csv.hpp"
#include "io/document.hpp"
#include "io/json/json.hpp"
#include "io/open.hpp"

namespace keyrot::test {

/// `text` read whole as compare and info read it; Euler keys in ZYX unless
/// `o` says otherwise.
inline document read(std::string_view text, format f, read_options o = {}) {
    std::ostringstream err;
    o.source = "in";
    if (!o.settings.euler) o.settings.euler = parse_euler_seq("ZYX");
    warnings warn(err, o.source);
    std::istringstream in{std::string(text)};
    return read_document(in, f, o, warn);
}

inline document read(std::string_view text, format f, quat_order order) {
    read_options o;
    o.order = order;
    return read(text, f, o);
}

/// Every key a reader gives, and the message it stops with ("" at the end).
struct reading_result {
    std::vector<std::pair<std::string, raw_key>> keys;
    std::string error;
};

inline reading_result read_all(key_reader& reader, std::size_t at_most = SIZE_MAX) {
    reading_result r;
    std::string name;
    raw_key k;
    try {
        while (r.keys.size() < at_most && reader.next(name, k)) r.keys.emplace_back(name, k);
    } catch (const input_error& e) {
        r.error = e.what();
    }
    return r;
}

/// The raw keys of `text` (track name and key) as make_key_reader gives
/// them to the commands, before they become rotations.
inline std::vector<std::pair<std::string, raw_key>> read_keys(std::string_view text, format f, warnings& warn) {
    read_options o;
    o.source = "in";
    std::istringstream in{std::string(text)};
    const auto reader = make_key_reader(in, f, o, warn);
    std::vector<std::pair<std::string, raw_key>> keys;
    std::string name;
    raw_key k;
    while (reader->next(name, k)) keys.emplace_back(name, k);
    return keys;
}

inline std::vector<std::pair<std::string, raw_key>> read_keys(std::string_view text, format f) {
    std::ostringstream err;
    warnings warn(err, "in");
    return read_keys(text, f, warn);
}

/// A JSON document's raw keys as read_json gives them (the document read
/// whole), track by track.
struct raw_json {
    struct track {
        raw_track header;
        std::vector<raw_key> keys;
    };
    std::vector<track> tracks;
    bool named = false;
};

inline raw_json read_json_keys(std::string_view text) {
    struct sink final : raw_key_sink {
        raw_json doc;
        void begin_track(raw_track header) override { doc.tracks.push_back({std::move(header), {}}); }
        void key(raw_key&& k) override { doc.tracks.back().keys.push_back(std::move(k)); }
    } keys;
    std::ostringstream err;
    warnings warn(err, "in");
    read_options o;
    o.source = "in";
    std::istringstream in{std::string(text)};
    keys.doc.named = read_json(in, o, keys, warn);
    return std::move(keys.doc);
}

/// The message reading `text` stops with; "" when it reads.
inline std::string error_of(std::string_view text, format f) {
    try {
        read(text, f);
    } catch (const input_error& e) {
        return e.what();
    }
    return "";
}

/// The writer of a text format (as open_table makes it, without the threads).
inline std::unique_ptr<table_writer> make_writer(format f, std::string& out, const table_info& info,
                                                 const write_options& w, warnings& warn) {
    if (f == format::csv) return make_csv_writer(out, info, w, warn);
    return make_json_writer(out, info, w, warn, f == format::ndjson);
}

inline std::string write(format f, const table_info& info, const write_options& w, const std::vector<table_row>& rows,
                         const std::string& track = "") {
    std::string out;
    std::ostringstream err;
    warnings warn(err, "in");
    auto writer = make_writer(f, out, info, w, warn);
    writer->begin_track(track, channels{rows.front().translation.has_value(), rows.front().scale.has_value()});
    for (const table_row& s : rows) writer->row(s);
    writer->finish();
    return out;
}

}  // namespace keyrot::test
