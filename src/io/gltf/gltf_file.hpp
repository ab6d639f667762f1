// SPDX-License-Identifier: MIT
#pragma once
// A glTF 2.0 file as it is stored: its JSON (from a .gltf, or a .glb's JSON
// chunk), and its buffers (the .glb's BIN chunk, base64 data: URIs, files
// beside it). Accessors: gltf_accessor.hpp.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <istream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/common/byte_block.hpp"
#include "io/common/format.hpp"

namespace keyrot {

using gltf_json = nlohmann::ordered_json;

struct gltf_file {
    std::string source;     ///< for messages
    std::string directory;  ///< where relative buffer URIs point: the file's, "." for standard input
    std::size_t max_bytes = default_max_bytes;  ///< the most a buffer file may hold
    gltf_json json;
    byte_block glb;                                          ///< a .glb as read, its BIN chunk in place
    std::optional<std::pair<std::size_t, std::size_t>> bin;  ///< the BIN chunk's offset and size in `glb`
    std::vector<std::optional<std::string>> buffers;         ///< the others' bytes, each as it is first read
};

/// The file's JSON, and a .glb's BIN chunk (`f`: gltf or glb). Checks the
/// container, asset.version 2 and extensionsRequired; buffers are read when
/// an accessor needs them. Throws input_error: "walk.glb: truncated GLB: the
/// header says 5000 bytes, the file has 4000".
gltf_file load_gltf(std::istream& in, format f, const std::string& source, const std::string& directory,
                    std::size_t max_bytes);

/// Buffer `i`'s bytes (the BIN chunk, a data: URI's, a file's), read on
/// first use. Precondition: i indexes buffers.
std::string_view buffer_bytes(gltf_file& file, std::size_t i);

/// The little-endian unsigned integer of `bytes` (1 to 4) bytes at `p`, as
/// glTF stores every number.
std::uint32_t little_endian(const char* p, int bytes);

/// An extension that changes nothing keyrot reads or writes of an
/// animation (a material's, a texture's, a light's): a file that requires
/// any other is refused.
bool harmless_extension(std::string_view name);

/// The array `name` of the file's JSON ("nodes"), empty when there is none.
const gltf_json& top_array(const gltf_file& file, const char* name);

/// Member `name` of `object` as a non-negative integer, `fallback` where
/// there is none; an input_error at `at` for anything else.
std::size_t unsigned_member(const gltf_json& object, const char* name, std::size_t fallback, const std::string& at);

/// Member `name` of `object` as a string, `fallback` where there is none;
/// an input_error at `at` for anything else.
std::string string_member(const gltf_json& object, const char* name, std::string_view fallback, const std::string& at);

/// `value` as an index into `array` (of `what`: "node"), or an input_error at `path`.
std::size_t index_into(const gltf_file& file, const gltf_json& value, const char* array, const std::string& path);

}  // namespace keyrot
