// SPDX-License-Identifier: MIT
#pragma once
// A JSON document's keys as they arrive, block by block.
#include <istream>
#include <memory>

#include "io/common/line_keys.hpp"

namespace keyrot {

/// A document's keys one at a time, read in blocks, so that a long track
/// needs no more memory than a few keys. Only for documents whose settings
/// fields come before their keys and whose text flat_json takes; any other
/// it declines (next() returns false, declined() true) for read_json to
/// read whole. It throws input_error for the errors it meets, and read_json
/// then says what is wrong, in its own order.
std::unique_ptr<line_key_reader> make_json_reader(std::istream& in, const read_options& opts, warnings& warn);

}  // namespace keyrot
