// SPDX-License-Identifier: MIT
#include "io/gltf/gltf_buffer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>

namespace keyrot::detail {
namespace {

/// `bytes` in base64 appended to `out`.
void append_base64(std::string& out, std::string_view bytes) {
    static constexpr char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const auto byte = [&](std::size_t j) {
            return j < bytes.size() ? std::uint32_t{static_cast<unsigned char>(bytes[j])} : 0u;
        };
        const std::uint32_t v = byte(i) << 16 | byte(i + 1) << 8 | byte(i + 2);
        out += digits[v >> 18 & 63];
        out += digits[v >> 12 & 63];
        out += i + 1 < bytes.size() ? digits[v >> 6 & 63] : '=';
        out += i + 2 < bytes.size() ? digits[v & 63] : '=';
    }
}

}  // namespace

void append_float(std::string& out, float v) {
    std::uint32_t raw;
    std::memcpy(&raw, &v, 4);
    char bytes[4];  // (appended at once: a character at a time costs a check each)
    for (std::size_t b = 0; b < 4; ++b) bytes[b] = static_cast<char>(raw >> (8 * b) & 0xff);
    out.append(bytes, 4);
}

void append_normalized_shorts(std::string& out, std::span<const double, 4> q) {
    constexpr double scale = 32767;
    std::array<double, 4> down{};
    for (std::size_t i = 0; i < 4; ++i) down[i] = std::clamp(std::floor(q[i] * scale), -scale, scale - 1);
    // Candidate `up` rounds component i up where its bit i is set. (Lengths
    // squared are sums of squared integers: exact.)
    std::array<double, 16> dot{}, length2{};
    for (std::size_t i = 0; i < 4; ++i)
        for (unsigned up = 0; up < 16; ++up) {
            const double c = down[i] + (up >> i & 1);
            dot[up] += c * q[i], length2[up] += c * c;
        }
    // The nearest in angle has the largest cos² = (c·q)² / (c·c), c·q > 0;
    // cos² within rounding of the best so far counts as a tie. From the
    // one rounded to nearest, which is always among them.
    unsigned best = 0;
    for (std::size_t i = 0; i < 4; ++i) best |= (q[i] * scale - down[i] >= 0.5 ? 1u : 0u) << i;
    double best_cos2 = dot[best] * dot[best] / length2[best], best_off = std::fabs(length2[best] - scale * scale);
    for (unsigned up = 0; up < 16; ++up) {
        const double cos2 = dot[up] * dot[up] / length2[up], off = std::fabs(length2[up] - scale * scale);
        if (!(dot[up] > 0 && length2[up] >= (scale - 1) * (scale - 1) && length2[up] <= (scale + 1) * (scale + 1)))
            continue;
        const bool tie = std::fabs(cos2 - best_cos2) <= 1e-15;
        if ((!tie && cos2 > best_cos2) || (tie && off < best_off)) best = up, best_cos2 = cos2, best_off = off;
    }
    char bytes[8];
    for (std::size_t i = 0; i < 4; ++i) {
        const auto s = static_cast<std::uint16_t>(static_cast<std::int16_t>(down[i] + (best >> i & 1)));
        bytes[2 * i] = static_cast<char>(s & 0xff), bytes[2 * i + 1] = static_cast<char>(s >> 8);
    }
    out.append(bytes, 8);
}

float single(double v, const std::string& where, const char* what) {
    const auto f = static_cast<float>(v);
    if (!std::isfinite(f))
        throw input_error(where, fmt::format("{} {} is beyond a 32-bit float: expected what glTF can store", what, v));
    return f;
}

std::string one_float_apart(double a, double b) {
    return fmt::format("times {} s and {} s are one 32-bit float, as glTF stores them: expected keys further apart "
                       "(a lower --fps)",
                       a, b);
}

const char* interpolation_name(method m) {
    return m == method::step ? "STEP" : m == method::cubicspline ? "CUBICSPLINE" : "LINEAR";
}

std::size_t buffer_builder::view(std::string_view data, std::size_t remainder) {
    const std::size_t v = begin_view(data.size(), remainder);
    bin.append(data);
    return v;
}

std::size_t buffer_builder::view(byte_spool& data) {
    const std::size_t v = begin_view(data.size(), 0);
    data.each_block([this](std::string_view block) { bin.append(block); });
    return v;
}

std::size_t buffer_builder::accessor(const std::vector<float>& values, std::size_t width, bool bounds) {
    std::string data;
    data.reserve(values.size() * 4);
    for (const float v : values) append_float(data, v);
    std::vector<float> lo, hi;
    if (bounds) {
        lo.assign(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(width)), hi = lo;
        for (std::size_t i = 0; i < values.size(); ++i)
            lo[i % width] = std::min(lo[i % width], values[i]), hi[i % width] = std::max(hi[i % width], values[i]);
    }
    return accessor(data, values.size() / width, width, component::float32, lo, hi);
}

std::size_t buffer_builder::accessor(std::string_view data, std::size_t count, std::size_t width, component c,
                                     const std::vector<float>& lo, const std::vector<float>& hi) {
    if (!shared_) return accessor(view(data), count, width, lo, hi, c);
    if (!shared_->index) shared_->index = begin_view(0, 0), shared_->start = bin.size();
    const std::size_t offset = bin.size() - shared_->start;
    // (floats, and shorts four to an element: the next accessor's offset stays a multiple of 4)
    bin.append(data);
    const std::size_t a = accessor(*shared_->index, count, width, lo, hi, c);
    if (offset != 0) json_["accessors"][a]["byteOffset"] = offset;
    return a;
}

void buffer_builder::end_shared_view() {
    if (shared_ && shared_->index) json_["bufferViews"][*shared_->index]["byteLength"] = bin.size() - shared_->start;
    shared_.reset();
}

std::size_t buffer_builder::accessor(std::size_t view, std::size_t count, std::size_t width,
                                     const std::vector<float>& lo, const std::vector<float>& hi, component c) {
    gltf_json a = gltf_json::object();
    a["bufferView"] = view;
    a["componentType"] = c == component::float32 ? 5126 : 5122;
    if (c == component::normalized_short) a["normalized"] = true;
    a["count"] = count;
    a["type"] = width == 1 ? "SCALAR" : width == 3 ? "VEC3" : "VEC4";
    if (!lo.empty()) a["min"] = lo, a["max"] = hi;
    return append("accessors", std::move(a));
}

std::size_t buffer_builder::begin_view(std::size_t length, std::size_t remainder) {
    while (bin.size() % 4 != remainder) bin.append(std::string_view("\0", 1));
    gltf_json v = gltf_json::object();
    v["buffer"] = 0;
    v["byteOffset"] = bin.size();
    v["byteLength"] = length;
    return append("bufferViews", std::move(v));
}

std::size_t buffer_builder::append(const char* name, gltf_json value) {
    if (!json_.contains(name)) json_[name] = gltf_json::array();
    json_[name].push_back(std::move(value));
    return json_[name].size() - 1;
}

void put_file(gltf_json& json, byte_spool& bin, format f, const std::optional<std::string>& target,
              commit_mode commit, std::ostream& out) {
    json["buffers"][0]["byteLength"] = bin.size();
    std::optional<output_file> file;
    if (target && f == format::glb) file.emplace(*target, commit);
    const auto put = [&](std::string_view piece) { file ? file->write(piece) : write_to_stream(out, piece); };
    if (f == format::glb) {
        std::string text = json.dump();
        text.append((4 - text.size() % 4) % 4, ' ');
        const std::size_t padding = (4 - bin.size() % 4) % 4, bin_chunk = bin.size() ? 8 + bin.size() + padding : 0;
        std::string head;
        const auto u32 = [&](std::size_t v) {
            for (int b = 0; b < 4; ++b) head += static_cast<char>(v >> (8 * b) & 0xff);
        };
        head += "glTF";
        u32(2), u32(12 + 8 + text.size() + bin_chunk), u32(text.size()), u32(0x4E4F534A);
        put(head), put(text);
        if (bin.size()) {
            head.clear();
            u32(bin.size() + padding), u32(0x004E4942);
            put(head);
            bin.each_block(put);
            put(std::string(padding, '\0'));
        }
        if (file) file->commit();
        return;
    }
    if (!target) {
        // The data: URI's base64, 3 bytes to 4 characters, spliced in where the JSON text holds a marker.
        const std::string uri = "data:application/octet-stream;base64,", marker = "\x01";
        json["buffers"][0]["uri"] = uri + marker;
        const std::string text = json.dump() + "\n";
        const std::size_t at = text.find(uri + "\\u0001");
        put(std::string_view(text).substr(0, at + uri.size()));
        std::string carry, encoded;  // (one buffer each, whatever the buffer's length)
        bin.each_block([&](std::string_view block) {
            carry += block;
            const std::size_t whole = carry.size() / 3 * 3;
            encoded.clear();
            append_base64(encoded, std::string_view(carry).substr(0, whole));
            put(encoded);
            carry.erase(0, whole);
        });
        encoded.clear();
        append_base64(encoded, carry);
        put(encoded);
        put(std::string_view(text).substr(at + uri.size() + 6));
        return;
    }
    const std::filesystem::path bin_path = std::filesystem::path(*target).replace_extension(".bin");
    json["buffers"][0]["uri"] = bin_path.filename().string();
    output_file bin_file(bin_path.string(), commit), gltf_file_out(*target, commit);
    bin.each_block([&](std::string_view block) { bin_file.write(block); });
    gltf_file_out.write(json.dump() + "\n");
    bin_file.commit();
    gltf_file_out.commit();
}


}  // namespace keyrot::detail
