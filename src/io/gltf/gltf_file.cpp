// SPDX-License-Identifier: MIT
#include "io/gltf/gltf_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include "io/json/json.hpp"
#include "keyrot/error.hpp"

namespace keyrot {

std::uint32_t little_endian(const char* p, int bytes) {
    if (bytes == 4 && std::endian::native == std::endian::little) {  // (every FLOAT: one load)
        std::uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
    std::uint32_t v = 0;
    for (int i = bytes - 1; i >= 0; --i) v = v << 8 | static_cast<unsigned char>(p[i]);
    return v;
}

namespace {

constexpr std::uint32_t glb_json_chunk = 0x4E4F534A, glb_bin_chunk = 0x004E4942;

// A GLB header: the magic, then the version and the stated length of the
// file, each 4 bytes; the chunks follow.
constexpr std::size_t glb_version_at = 4, glb_length_at = 8, glb_header_bytes = 12;

/// A .glb's chunks: the JSON text, and the BIN chunk if there is one.
std::pair<std::string_view, std::optional<std::string_view>> glb_chunks(std::string_view bytes,
                                                                        const std::string& source) {
    if (bytes.size() < glb_header_bytes)
        throw input_error(source, fmt::format("truncated GLB: {} bytes, expected a {}-byte header", bytes.size(),
                                              glb_header_bytes));
    if (bytes.substr(0, 4) != "glTF")
        throw input_error(source, "not a GLB file: expected the magic 'glTF' at its start");
    if (const auto version = little_endian(bytes.data() + glb_version_at, 4); version != 2)
        throw input_error(source, fmt::format("GLB version {}: expected 2 (glTF 2.0)", version));
    const std::size_t length = little_endian(bytes.data() + glb_length_at, 4);
    if (length > bytes.size())
        throw input_error(
            source, fmt::format("truncated GLB: the header says {} bytes, the file has {}", length, bytes.size()));
    if (length < bytes.size())
        throw input_error(source, fmt::format("GLB of {} bytes has {} more after its end: expected the length its "
                                              "header states",
                                              length, bytes.size() - length));
    std::string_view json;
    std::optional<std::string_view> bin;
    for (std::size_t at = glb_header_bytes, n = 0; at < length; ++n) {
        if (length - at < 8) throw input_error(source, fmt::format("truncated GLB: chunk {} has no full header", n));
        const std::size_t size = little_endian(bytes.data() + at, 4);
        const std::uint32_t type = little_endian(bytes.data() + at + 4, 4);
        if (size > length - at - 8)
            throw input_error(source, fmt::format("GLB chunk {} of {} bytes runs past the end of the file", n, size));
        const std::string_view data = bytes.substr(at + 8, size);
        if (n == 0 && type != glb_json_chunk)
            throw input_error(source, "GLB's first chunk is not JSON: expected a JSON chunk");
        if (n == 0) json = data;
        if (n == 1 && type == glb_bin_chunk) bin = data;  // other chunk types are to be ignored
        at += 8 + size;
    }
    if (json.empty()) throw input_error(source, "GLB has no JSON chunk: expected one");
    return {json, bin};
}

void check_header(const gltf_json& json, const std::string& source) {
    if (!json.is_object()) throw input_error(source, "expected a glTF JSON object");
    const auto asset = json.find("asset");
    if (asset == json.end() || !asset->is_object() || !asset->contains("version") || !(*asset)["version"].is_string())
        throw input_error(source, "asset.version: expected the glTF version, \"2.0\"");
    const std::string version = (*asset)["version"];
    const std::string min_version = string_member(*asset, "minVersion", version, where(source, "asset"));
    if (!version.starts_with("2.") || !min_version.starts_with("2."))
        throw input_error(source, fmt::format("asset.version: glTF {}: expected 2.0", excerpt(version)));
    if (const auto required = json.find("extensionsRequired"); required != json.end() && required->is_array())
        for (std::size_t i = 0; i < required->size(); ++i)
            if (const auto& name = (*required)[i]; !name.is_string() || !harmless_extension(name.get<std::string>()))
                throw input_error(source, fmt::format("extensionsRequired[{}]: {} changes what keyrot reads: expected "
                                                      "a file without it (decompress it first)",
                                                      i, excerpt(name.dump())));
}

std::string percent_decoded(std::string_view uri) {
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        const auto hex = [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; };
        if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) && hex(uri[i + 2])) {
            out += static_cast<char>(std::stoi(std::string(uri.substr(i + 1, 2)), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

/// The bytes of a base64 text, or nothing where it is not base64.
std::optional<std::string> base64_decoded(std::string_view text) {
    const auto value = [](char c) -> int {
        if (c >= 'A' && c <= 'Z') return c - 'A';
        if (c >= 'a' && c <= 'z') return c - 'a' + 26;
        if (c >= '0' && c <= '9') return c - '0' + 52;
        if (c == '+') return 62;
        if (c == '/') return 63;
        return -1;
    };
    while (!text.empty() && text.back() == '=' && text.size() % 4 != 1) text.remove_suffix(1);
    if (text.size() % 4 == 1) return std::nullopt;
    std::string out;
    out.reserve(text.size() * 3 / 4);
    std::uint32_t bits = 0;
    int held = 0;
    for (const char c : text) {
        const int v = value(c);
        if (v < 0) return std::nullopt;
        bits = bits << 6 | static_cast<std::uint32_t>(v);
        if ((held += 6) >= 8) out += static_cast<char>(bits >> (held -= 8) & 0xff);
    }
    return out;
}

}  // namespace

std::string_view buffer_bytes(gltf_file& file, std::size_t i) {
    if (file.buffers.size() <= i) file.buffers.resize(i + 1);
    if (file.buffers[i]) return *file.buffers[i];
    const gltf_json& b = top_array(file, "buffers")[i];
    const std::string at = where(file.source, fmt::format("buffers[{}]", i));
    if (!b.is_object() || !b.contains("byteLength") || !b["byteLength"].is_number_unsigned())
        throw input_error(at, "expected an object with a byteLength");
    const std::size_t length = b["byteLength"];
    std::string bytes;
    if (!b.contains("uri")) {
        if (i != 0 || !file.bin)
            throw input_error(at, "no uri, and the file has no GLB BIN chunk: expected one of them");
        const std::string_view chunk = file.glb.view().substr(file.bin->first, file.bin->second);
        if (chunk.size() < length)
            throw input_error(at, fmt::format("holds {} bytes: expected byteLength {}", chunk.size(), length));
        return chunk;  // where it is
    } else if (!b["uri"].is_string()) {
        throw input_error(at, "uri: expected a string");
    } else if (const std::string uri = b["uri"]; uri.starts_with("data:")) {
        const auto comma = uri.find(',');
        const std::optional<std::string> decoded =
            comma != std::string::npos && uri.substr(0, comma).ends_with(";base64")
                ? base64_decoded(std::string_view(uri).substr(comma + 1))
                : std::nullopt;
        if (!decoded)
            throw input_error(at, "uri: expected a base64 data: URI ('data:application/octet-stream;base64,...')");
        bytes = *decoded;
    } else {
        if (uri.find("://") != std::string::npos || uri.starts_with("/"))
            throw input_error(
                at, fmt::format("uri '{}': expected a file beside the glTF file (a relative URI)", excerpt(uri)));
        const std::filesystem::path name = std::filesystem::path(file.directory) / percent_decoded(uri);
        if (length > file.max_bytes)
            throw input_error(at, fmt::format("byteLength {}: expected at most {} bytes (--max-bytes N raises the "
                                              "limit)",
                                              length, file.max_bytes));
        std::ifstream in(name, std::ios::binary);
        if (!in) throw input_error(at, fmt::format("cannot read '{}'", name.string()));
        // byteLength bytes and no more: what follows is not the buffer's, and
        // a name like ../../dev/zero has no end.
        bytes.resize(length);
        in.read(bytes.data(), static_cast<std::streamsize>(length));
        bytes.resize(static_cast<std::size_t>(in.gcount()));
    }
    if (bytes.size() < length)
        throw input_error(at, fmt::format("holds {} bytes: expected byteLength {}", bytes.size(), length));
    file.buffers[i] = std::move(bytes);
    return *file.buffers[i];
}

namespace {

/// Whether `start` (the first bytes read) could begin a glTF file: a GLB's
/// magic and version 2, or a JSON object.
bool could_begin_gltf(std::string_view start, format f) {
    if (f == format::glb)
        return std::string_view("glTF").starts_with(start.substr(0, 4)) &&
               (start.size() < glb_version_at + 4 || little_endian(start.data() + glb_version_at, 4) == 2);
    return could_begin_json(start, "{");
}

}  // namespace

std::size_t unsigned_member(const gltf_json& object, const char* name, std::size_t fallback, const std::string& at) {
    if (!object.is_object()) throw input_error(at, "expected an object");
    const auto it = object.find(name);
    if (it == object.end()) return fallback;
    if (!it->is_number_unsigned()) throw input_error(at, fmt::format("{}: expected a non-negative integer", name));
    return *it;
}

std::string string_member(const gltf_json& object, const char* name, std::string_view fallback, const std::string& at) {
    if (!object.is_object()) throw input_error(at, "expected an object");
    const auto it = object.find(name);
    if (it == object.end()) return std::string(fallback);
    if (!it->is_string()) throw input_error(at, fmt::format("{}: expected a string", name));
    return *it;
}

/// Extensions that change nothing keyrot reads or writes of an animation:
/// a file that requires any other is refused.
bool harmless_extension(std::string_view name) {
    static const std::set<std::string, std::less<>> harmless = {"KHR_materials_clearcoat",
                                                                "KHR_materials_emissive_strength",
                                                                "KHR_materials_ior",
                                                                "KHR_materials_iridescence",
                                                                "KHR_materials_sheen",
                                                                "KHR_materials_specular",
                                                                "KHR_materials_transmission",
                                                                "KHR_materials_unlit",
                                                                "KHR_materials_variants",
                                                                "KHR_materials_volume",
                                                                "KHR_mesh_quantization",
                                                                "KHR_texture_basisu",
                                                                "KHR_texture_transform",
                                                                "KHR_lights_punctual",
                                                                "EXT_texture_webp"};
    return harmless.contains(name);
}

const gltf_json& top_array(const gltf_file& file, const char* name) {
    static const gltf_json empty = gltf_json::array();
    const auto it = file.json.find(name);
    return it != file.json.end() && it->is_array() ? *it : empty;
}

std::size_t index_into(const gltf_file& file, const gltf_json& value, const char* array, const std::string& path) {
    const std::size_t size = top_array(file, array).size();
    if (!value.is_number_unsigned() || value.get<std::size_t>() >= size)
        throw input_error(path, fmt::format("{}: expected an index into {} (0 to {})", excerpt(value.dump()), array,
                                            size == 0 ? std::string("none") : std::to_string(size - 1)));
    return value;
}

gltf_file load_gltf(std::istream& in, format f, const std::string& source, const std::string& directory,
                    std::size_t max_bytes) {
    gltf_file file{source, directory, max_bytes, {}, {}, std::nullopt, {}};
    byte_block bytes;
    // In one piece where the stream knows its size (a file; keyrot's own
    // input streams say what is left), then, where it could not seek, a
    // piece at a time to its end.
    in.seekg(0, std::ios::end);
    std::streamoff size = in.tellg();
    const bool seekable = in && size >= 0;
    in.clear();
    in.seekg(0);
    in.clear();
    if (!seekable) size = in.rdbuf()->in_avail();
    if (size > 0) bytes.read(in, std::min(static_cast<std::size_t>(size), max_bytes + 1));
    // Input that cannot begin a glTF file (/dev/zero, random bytes) is not
    // read on to the limit: what came is parsed, which says what is wrong.
    if (!seekable) {
        constexpr std::size_t block = std::size_t{1} << 16;
        if (bytes.size() < block) bytes.read(in, block - bytes.size());
        if (could_begin_gltf(bytes.view().substr(0, block), f)) {
            // Nor is a .glb whose header states a length past the limit (where
            // the input goes on: one read whole is said to be truncated).
            if (f == format::glb && bytes.size() >= glb_header_bytes && in.peek() != std::istream::traits_type::eof())
                if (const std::size_t stated = little_endian(bytes.view().data() + glb_length_at, 4); stated > max_bytes)
                    throw input_error(source, fmt::format("GLB header states {} bytes, more than {}: expected a "
                                                          "smaller file (--max-bytes N raises the limit)",
                                                          stated, max_bytes));
            while (bytes.size() <= max_bytes && bytes.read(in, block)) {
            }
        }
    }
    if (bytes.size() > max_bytes)
        throw input_error(
            source,
            fmt::format("more than {} bytes: expected a smaller file (--max-bytes N raises the limit)", max_bytes));
    std::string_view json = bytes.view();
    if (f == format::glb) {
        const auto [text, bin] = glb_chunks(json, source);
        if (bin) file.bin = std::pair(static_cast<std::size_t>(bin->data() - json.data()), bin->size());
        json = text;
    }
    file.json = parse_json_text(json, source);
    check_header(file.json, source);
    if (f == format::glb) file.glb = std::move(bytes);
    return file;
}

}  // namespace keyrot
