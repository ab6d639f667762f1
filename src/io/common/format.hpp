// SPDX-License-Identifier: MIT
#pragma once
// The file formats by name, by extension, and by content.
#include <array>
#include <optional>
#include <string_view>

#include "keyrot/names.hpp"

namespace keyrot {

/// Key tables (csv, json, ndjson) and animation files: glTF 2.0 as JSON
/// with its buffers (gltf) or binary (glb), and BVH motion capture.
enum class format { csv, json, ndjson, gltf, glb, bvh };
template <>
inline constexpr std::array<enum_name<format>, 6> names_of<format> = {{{format::csv, "csv"},
                                                                      {format::json, "json"},
                                                                      {format::ndjson, "ndjson"},
                                                                      {format::gltf, "gltf"},
                                                                      {format::glb, "glb"},
                                                                      {format::bvh, "bvh"}}};
/// glTF 2.0, JSON or binary.
constexpr bool is_gltf(format f) noexcept { return f == format::gltf || f == format::glb; }
/// Most bytes a JSON document or a glTF file read whole may take
/// (--max-bytes): endless input (/dev/zero) ends in an error, not in all memory.
inline constexpr std::size_t default_max_bytes = std::size_t{256} << 20;
/// Most bytes a line of CSV, NDJSON or BVH may take unless --max-bytes says:
/// far more than any keyframe's line, far less than memory.
inline constexpr std::size_t default_max_line_bytes = std::size_t{1} << 20;

/// ".csv" -> csv, ".json" -> json, ".ndjson" / ".jsonl" -> ndjson, ".gltf", ".glb", ".bvh".
std::optional<format> format_of_path(std::string_view path);
/// Guess from the start of the content: the GLB magic "glTF" means glb;
/// HIERARCHY first means bvh; an
/// object with an "asset" object and a "version" means gltf; '{' or '['
/// first means JSON, unless the first line is a whole object and more lines
/// follow (NDJSON); else CSV.
format sniff_format(std::string_view start);

}  // namespace keyrot
