// SPDX-License-Identifier: MIT
#include "io/gltf/gltf_accessor.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <optional>
#include <tuple>
#include <utility>

#include "keyrot/error.hpp"
#include "keyrot/track.hpp"

namespace keyrot {
namespace {

/// Packed 32-bit floats of the host's byte order at any alignment, read as
/// doubles: a forward iterator, so that vector::assign sizes its vector
/// once and fills it, where resize would zero it first.
struct packed_floats {
    using iterator_category = std::forward_iterator_tag;
    using value_type = double;
    using difference_type = std::ptrdiff_t;
    using pointer = void;  // (no operator->: each element is made as it is read)
    using reference = double;
    const char* at = nullptr;
    double operator*() const noexcept {
        float f;
        std::memcpy(&f, at, 4);
        return f;
    }
    packed_floats& operator++() noexcept { return at += 4, *this; }
    packed_floats operator++(int) noexcept { return {std::exchange(at, at + 4)}; }
    bool operator==(const packed_floats&) const = default;
};

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
    if (!stored) {
        values.assign(count * n, 0.0);
    } else if (code == 5126 && stride == element && std::endian::native == std::endian::little) {
        // Packed floats, as nearly every exporter writes them: widened in one
        // loop the compiler vectorises, not a component at a time through
        // decoded() (a take's accessors are most of what is read).
        const packed_floats from{bytes.data() + offset};
        values.assign(from, packed_floats{from.at + 4 * count * n});
    } else {
        values.resize(count * n);
        for (std::size_t i = 0; i < count; ++i)
            for (std::size_t j = 0; j < n; ++j)
                values[i * n + j] = decoded(bytes.data() + offset + i * stride + j * static_cast<std::size_t>(c->bytes),
                                            *c, normalized);
    }
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
