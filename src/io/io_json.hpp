#pragma once
// JSON documents ({"keys": [...]}, {"frames": [...]}, {"tracks": {...}} or a
// bare array of keys) and NDJSON (one key or frame object per line).
#include <istream>
#include <memory>
#include <string>

#include "io/io.hpp"

namespace keyrot {

/// The whole document at once (memory about four times its size), tracks
/// in its order. Throws input_error "<source>: tracks.hip.keys[3]: ..." for
/// bad content, "<source>:<line>: ..." for malformed JSON.
raw_document read_json(std::istream& in, const read_options& opts, warnings& warn);
/// The same document's tracks and keys handed to `sink` in its order; returns
/// whether it names its tracks.
bool read_json(std::istream& in, const read_options& opts, raw_key_sink& sink, warnings& warn);
/// Thrown by make_json_reader's reader for a document it does not read as
/// read_json would: the caller then reads it whole.
struct json_not_streamed : error {
    json_not_streamed() : error("the JSON document is read whole") {}
};
/// A document's keys one at a time, read in blocks, so that a long track
/// needs no more memory than a few keys. Only for documents whose settings
/// fields come before their keys and whose text flat_json takes; for any
/// other, and for any error, it throws (json_not_streamed, input_error), and
/// read_json then says what is wrong.
std::unique_ptr<key_reader> make_json_reader(std::istream& in, const read_options& opts, warnings& warn);
/// One line at a time. Throws input_error "<source>:<line>: ...".
std::unique_ptr<key_reader> make_ndjson_reader(std::istream& in, const read_options& opts, warnings& warn);

std::unique_ptr<table_writer> make_json_writer(std::string& out, const table_info& info,
                                               const write_options& opts, warnings& warn, bool lines);

}  // namespace keyrot
