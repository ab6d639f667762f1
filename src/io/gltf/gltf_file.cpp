#include "io/gltf/gltf_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <tuple>

#include "io/json/json.hpp"
#include "keyrot/error.hpp"

namespace keyrot {
namespace {

/// Little-endian unsigned integer of `bytes` bytes at `p`.
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

struct component_type {
    int code;
    int bytes;
    bool is_signed;
};

std::optional<component_type> component_of(int code) {
    switch (code) {
        case 5120:
            return component_type{code, 1, true};
        case 5121:
            return component_type{code, 1, false};
        case 5122:
            return component_type{code, 2, true};
        case 5123:
            return component_type{code, 2, false};
        case 5125:
            return component_type{code, 4, false};
        case 5126:
            return component_type{code, 4, true};
        default:
            return std::nullopt;
    }
}

/// Component `p` as the specification decodes it: a float as stored, a
/// normalised integer c as c / max (at least -1), any other integer as is.
double decoded(const char* p, component_type c, bool normalized) {
    const std::uint32_t raw = little_endian(p, c.bytes);
    if (c.code == 5126) {
        float f;
        static_assert(sizeof f == 4);
        std::memcpy(&f, &raw, 4);
        return f;
    }
    double v = raw;
    if (c.is_signed && raw >> (8 * c.bytes - 1)) v -= std::ldexp(1.0, 8 * c.bytes);
    if (!normalized) return v;
    const double max = std::ldexp(1.0, 8 * c.bytes - (c.is_signed ? 1 : 0)) - 1;
    return std::max(v / max, -1.0);
}

std::size_t components_of(std::string_view type) {
    if (type == "SCALAR") return 1;
    if (type == "VEC2") return 2;
    if (type == "VEC3") return 3;
    if (type == "VEC4") return 4;
    if (type == "MAT2") return 4;
    if (type == "MAT3") return 9;
    if (type == "MAT4") return 16;
    return 0;
}

/// The bytes of bufferView `view` (checked against its buffer), and its stride.
std::pair<std::string_view, std::size_t> buffer_view(gltf_file& file, const gltf_json& view, const std::string& at) {
    const std::size_t v = index_into(file, view, "bufferViews", at);
    const gltf_json& bv = top_array(file, "bufferViews")[v];
    const std::string here = where(file.source, fmt::format("bufferViews[{}]", v));
    if (!bv.is_object() || !bv.contains("buffer")) throw input_error(here, "expected an object with a buffer");
    const std::size_t b = index_into(file, bv["buffer"], "buffers", here);
    const std::string_view bytes = buffer_bytes(file, b);
    const std::size_t offset = unsigned_member(bv, "byteOffset", 0, here);
    const std::size_t length = unsigned_member(bv, "byteLength", 0, here);
    if (offset > bytes.size() || length > bytes.size() - offset)
        throw input_error(here, fmt::format("bytes {} to {} read past the end of buffer {} ({} bytes)", offset,
                                            offset + length, b, bytes.size()));
    return {bytes.substr(offset, length), unsigned_member(bv, "byteStride", 0, here)};
}

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

namespace {

/// Accessor `index` of the file, and how messages name it.
std::pair<const gltf_json&, std::string> accessor_at(const gltf_file& file, const gltf_json& index,
                                                     const std::string& path) {
    const std::string at = where(file.source, path);
    const std::size_t a = index_into(file, index, "accessors", at);
    const gltf_json& acc = top_array(file, "accessors")[a];
    std::string here = where(at, fmt::format("accessor {}", a));
    if (!acc.is_object()) throw input_error(here, "expected an object");
    return {acc, std::move(here)};
}

std::size_t count_of(const gltf_json& acc, const std::string& here) {
    const std::size_t count = unsigned_member(acc, "count", 0, here);
    if (count == 0) throw input_error(here, "count: expected at least 1 element");
    return count;
}

/// An accessor's sparse substitutes: `count` indices of `index_bytes`
/// each, and as many elements of `element` bytes.
struct sparse_part {
    std::size_t count, index_bytes;
    std::string_view indices, values;
};

std::optional<sparse_part> sparse_of(gltf_file& file, const gltf_json& acc, const std::string& here, std::size_t count,
                                     std::size_t element) {
    const auto sparse = acc.find("sparse");
    if (sparse == acc.end()) return std::nullopt;
    const std::string there = here + " sparse";
    if (!sparse->is_object() || !sparse->contains("indices") || !sparse->contains("values"))
        throw input_error(there, "expected count, indices and values");
    const std::size_t k = unsigned_member(*sparse, "count", 0, there);
    const gltf_json& indices = (*sparse)["indices"];
    const gltf_json& substitutes = (*sparse)["values"];
    if (k == 0 || k > count) throw input_error(there, fmt::format("count {}: expected 1 to {}", k, count));
    if (!indices.is_object() || !indices.contains("bufferView") || !substitutes.is_object() ||
        !substitutes.contains("bufferView"))
        throw input_error(there, "indices and values: expected objects with a bufferView");
    const int index_code = indices.contains("componentType") && indices["componentType"].is_number_integer()
                               ? indices["componentType"].get<int>()
                               : 0;
    const std::optional<component_type> ic = component_of(index_code);
    if (!ic || ic->is_signed)
        throw input_error(there,
                          fmt::format("indices.componentType {}: expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT",
                                      index_code));
    const auto [index_bytes, s1] = buffer_view(file, indices["bufferView"], there);
    const auto [value_bytes, s2] = buffer_view(file, substitutes["bufferView"], there);
    const std::size_t io = unsigned_member(indices, "byteOffset", 0, there),
                      vo = unsigned_member(substitutes, "byteOffset", 0, there);
    const auto width = static_cast<std::size_t>(ic->bytes);
    if (io > index_bytes.size() || k > (index_bytes.size() - io) / width || vo > value_bytes.size() ||
        k > (value_bytes.size() - vo) / element)
        throw input_error(there, fmt::format("{} substitutes read past the end of their bufferViews", k));
    return sparse_part{k, width, index_bytes.substr(io, k * width), value_bytes.substr(vo, k * element)};
}

}  // namespace

accessor_size size_of_accessor(const gltf_file& file, const gltf_json& index, const std::string& path) {
    const auto [acc, here] = accessor_at(file, index, path);
    const std::size_t count = count_of(acc, here);
    if (acc.contains("bufferView")) return {count, count};
    const auto sparse = acc.find("sparse");
    return {count, sparse != acc.end() && sparse->is_object() ? unsigned_member(*sparse, "count", 0, here + " sparse")
                                                              : 0};
}

void read_accessor(gltf_file& file, const gltf_json& index, const std::string& path, const accessor_kind& kind,
                   std::vector<double>& values) {
    const auto [acc, here] = accessor_at(file, index, path);
    const std::string type = string_member(acc, "type", "", here);
    if (type != kind.type) throw input_error(here, fmt::format("type '{}': expected {}", excerpt(type), kind.type));
    const int code =
        acc.contains("componentType") && acc["componentType"].is_number_integer() ? acc["componentType"].get<int>() : 0;
    const std::optional<component_type> c = component_of(code);
    const bool normalized =
        acc.contains("normalized") && acc["normalized"].is_boolean() && acc["normalized"].get<bool>();
    if (!c || !(code == 5126 || (kind.normalized_integers && normalized && c->bytes < 4)))
        throw input_error(
            here, fmt::format("componentType {}{}: expected FLOAT (5126){}", code, normalized ? ", normalized" : "",
                              kind.normalized_integers ? " or a normalised BYTE, UNSIGNED_BYTE, SHORT or "
                                                         "UNSIGNED_SHORT"
                                                       : ""));
    const std::size_t count = count_of(acc, here);
    const std::size_t n = components_of(type), element = n * static_cast<std::size_t>(c->bytes);
    // The count is checked against the bytes before anything is allocated:
    // a few bytes of JSON must not claim gigabytes.
    const bool stored = acc.contains("bufferView");
    std::string_view bytes;
    std::size_t stride = element, offset = 0;
    if (stored) {
        std::size_t byte_stride = 0;
        std::tie(bytes, byte_stride) = buffer_view(file, acc["bufferView"], here);
        if (byte_stride) stride = byte_stride;
        offset = unsigned_member(acc, "byteOffset", 0, here);
        if (stride < element)
            throw input_error(here, fmt::format("byteStride {} is less than an element's {} bytes", stride, element));
        if (offset > bytes.size() || (count - 1) > (bytes.size() - offset) / stride ||
            (count - 1) * stride + element > bytes.size() - offset)
            throw input_error(here, fmt::format("{} elements from byte {} read past the end of bufferView {}", count,
                                                offset, acc["bufferView"].get<std::size_t>()));
    } else if (count > values.max_size() / n) {  // all zeros but for sparse substitutes: no bytes bound the count
        throw input_error(here, fmt::format("count {}: expected at most {} elements", count, values.max_size() / n));
    }
    const std::optional<sparse_part> substitutes = sparse_of(file, acc, here, count, element);
    values.assign(count * n, 0.0);
    if (stored)
        for (std::size_t i = 0; i < count; ++i)
            for (std::size_t j = 0; j < n; ++j)
                values[i * n + j] = decoded(bytes.data() + offset + i * stride + j * static_cast<std::size_t>(c->bytes),
                                            *c, normalized);
    if (substitutes)
        for (std::size_t i = 0, previous = 0; i < substitutes->count; ++i) {
            const std::size_t e = little_endian(substitutes->indices.data() + i * substitutes->index_bytes,
                                                static_cast<int>(substitutes->index_bytes));
            if (e >= count || (i > 0 && e <= previous))
                throw input_error(here + " sparse", fmt::format("index {} at {}: expected strictly increasing indices "
                                                                "below {}",
                                                                e, i, count));
            previous = e;
            const char* const substitute = substitutes->values.data() + i * element;
            for (std::size_t j = 0; j < n; ++j)
                values[e * n + j] = decoded(substitute + j * static_cast<std::size_t>(c->bytes), *c, normalized);
        }
    for (std::size_t i = 0; i < values.size(); ++i)
        if (!std::isfinite(values[i]))
            throw input_error(here, fmt::format("element {} is not finite: expected finite numbers", i / n));
}

}  // namespace keyrot
