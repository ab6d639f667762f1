#pragma once
// A glTF 2.0 file as it is stored: its JSON (from a .gltf, or a .glb's JSON
// chunk), its buffers (the .glb's BIN chunk, base64 data: URIs, files
// beside it), and its accessors decoded as the specification says.
#include <nlohmann/json.hpp>

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

/// What a reader takes from an accessor: its type ("SCALAR", "VEC3",
/// "VEC4") and whether normalised BYTE, UNSIGNED_BYTE, SHORT and
/// UNSIGNED_SHORT components are read (as well as FLOAT).
struct accessor_kind {
    std::string_view type;
    bool normalized_integers = false;
};

/// An accessor's count, and how many of its elements the file stores: all
/// with a bufferView; else its sparse substitutes, the rest being 0. So a
/// reader can check what the count claims before read_accessor allocates it.
struct accessor_size {
    std::size_t count, stored;
};
accessor_size size_of_accessor(const gltf_file& file, const gltf_json& index, const std::string& path);

/// The elements of accessor `index` (a JSON value, for its checks), their
/// components one after another, decoded as the specification says
/// (byteStride, normalised integers, sparse substitution). `path` names what
/// refers to it, for messages: "walk.glb: animations[0].samplers[2].output:
/// accessor 14 reads past the end of buffer 0".
/// They go into `values`, whose memory is reused.
void read_accessor(gltf_file& file, const gltf_json& index, const std::string& path, const accessor_kind& kind,
                   std::vector<double>& values);

/// Buffer `i`'s bytes (the BIN chunk, a data: URI's, a file's), read on
/// first use. Precondition: i indexes buffers.
std::string_view buffer_bytes(gltf_file& file, std::size_t i);

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
