// SPDX-License-Identifier: MIT
#pragma once
// Where a command opens its input and output in a format: the format's key
// reader or table writer, with the fast paths (src/io/fast) behind them.
#include <functional>
#include <istream>
#include <memory>
#include <optional>
#include <ostream>
#include <string>

#include "io/common/interface.hpp"
#include "io/common/table_writer.hpp"

namespace keyrot {

/// For format::csv, format::ndjson, glTF, or format::json where the document
/// allows (make_json_reader). Warnings (unknown columns) go to `warn`. With
/// `parse_ahead`, keys are parsed on threads of their own ahead of the
/// caller once more than a thousand have come and `parse_ahead()` (asked
/// once, then, on the caller's thread) says it pays; the caller must not
/// use `in` meanwhile.
std::unique_ptr<key_reader> make_key_reader(std::istream& in, format f, const read_options& opts, warnings& warn,
                                            std::function<bool()> parse_ahead = nullptr);

/// A table in format `f` into `path` (none: `out`), a glTF file
/// (make_gltf_table), or a BVH file of the hierarchy in opts.bvh (throws
/// input_error without one). Euler output warns once about gimbal lock
/// through `warn`.
std::unique_ptr<table_output> open_table(format f, const std::optional<std::string>& path, std::ostream& out,
                                         const table_info& info, const write_options& opts, warnings& warn);

/// Whether a table of format `f` puts out nothing before finish(): glTF
/// and BVH, whose headers need the last row. An error met while its rows
/// come then leaves nothing behind, wherever it writes.
bool written_at_finish(format f);

}  // namespace keyrot
