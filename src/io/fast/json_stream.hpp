#pragma once
// A JSON document's keys as they arrive, block by block.
#include <istream>
#include <memory>

#include "io/line_keys.hpp"

namespace keyrot {

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
std::unique_ptr<line_key_reader> make_json_reader(std::istream& in, const read_options& opts, warnings& warn);

}  // namespace keyrot
