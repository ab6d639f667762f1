// SPDX-License-Identifier: MIT
#pragma once
// JSON documents ({"keys": [...]}, {"frames": [...]}, {"tracks": {...}} or a
// bare array of keys) and NDJSON (one key or frame object per line).
#include <nlohmann/json_fwd.hpp>

#include <istream>
#include <memory>
#include <string>
#include <string_view>

#include "io/common/interface.hpp"
#include "io/common/line_keys.hpp"
#include "io/common/table_writer.hpp"

namespace keyrot {

/// A JSON text parsed whole, its members in their order. Nesting deeper
/// than 64 levels, and a name twice in one object, are refused. Throws
/// input_error "<source>:<line>:<column>: invalid JSON: ..." (lines counted
/// from `first_line`).
nlohmann::ordered_json parse_json_text(std::string_view text, std::string_view source, std::size_t first_line = 1);
/// Whether `start`, the first bytes read of a JSON text, could begin one
/// that opens with one of `openers`: white space so far (after any
/// byte-order mark), or an opener and no syntax error before the end of
/// what came, which no more text could mend. /dev/zero and random bytes
/// cannot: they are said at once, not after reading on to the limit.
bool could_begin_json(std::string_view start, std::string_view openers);

/// The whole document at once (memory about four times its size), its
/// tracks and keys handed to `sink` in its order; returns whether it names
/// its tracks. Throws input_error "<source>: tracks.hip.keys[3]: ..." for
/// bad content, "<source>:<line>: ..." for malformed JSON.
bool read_json(std::istream& in, const read_options& opts, raw_key_sink& sink, warnings& warn);
/// One line at a time. Throws input_error "<source>:<line>: ...".
std::unique_ptr<line_key_reader> make_ndjson_reader(std::istream& in, const read_options& opts, warnings& warn);

/// `text` as a JSON string literal, quotes included. Throws input_error for invalid UTF-8.
std::string json_quote(std::string_view text);

std::unique_ptr<table_writer> make_json_writer(std::string& out, const table_info& info,
                                               const write_options& opts, warnings& warn, bool lines);

}  // namespace keyrot
