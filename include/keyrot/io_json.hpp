#pragma once
// JSON documents ({"keys": [...]}, {"frames": [...]}, {"tracks": {...}} or a
// bare array of keys) and NDJSON (one key or frame object per line).
#include <memory>
#include <string>
#include <string_view>

#include "keyrot/io.hpp"

namespace keyrot {

/// Throws input_error "<source>: tracks.hip.keys[3]: ..." for bad content,
/// "<source>:<line>: ..." for malformed JSON.
raw_document read_json(std::string_view text, const read_options& opts, warnings& warn);
/// Throws input_error "<source>:<line>: ...".
raw_document read_ndjson(std::string_view text, const read_options& opts, warnings& warn);

std::unique_ptr<table_writer> make_json_writer(std::string& out, const table_info& info,
                                               const write_options& opts, warnings& warn, bool lines);

}  // namespace keyrot
