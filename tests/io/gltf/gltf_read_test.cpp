// SPDX-License-Identifier: MIT
// The glTF reader on files made here byte by byte: the keys of a rotation
// channel, accessors decoded as the glTF 2.0 specification says (normalised
// integers, byteStride), .gltf and .glb alike, errors that name the JSON
// path; and a .glb written by open_table reads back as it was written.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "helpers.hpp"
#include "io/gltf/gltf_accessor.hpp"
#include "io/open.hpp"
#include "reading.hpp"

namespace keyrot::test {
namespace {

/// Little-endian bytes of `v`, as glTF stores every component.
template <typename T>
void put(std::string& bytes, T v) {
    unsigned char b[sizeof v];
    std::memcpy(b, &v, sizeof v);  // (this machine is little-endian, as checked below)
    bytes.append(reinterpret_cast<const char*>(b), sizeof v);
}

std::string base64(const std::string& bytes) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const auto byte = [&](std::size_t j) { return j < bytes.size() ? std::uint32_t{static_cast<unsigned char>(bytes[j])} : 0u; };
        const std::uint32_t n = byte(i) << 16 | byte(i + 1) << 8 | byte(i + 2);
        out += digits[n >> 18 & 63];
        out += digits[n >> 12 & 63];
        out += i + 1 < bytes.size() ? digits[n >> 6 & 63] : '=';
        out += i + 2 < bytes.size() ? digits[n & 63] : '=';
    }
    return out;
}

/// A file of one node "head" whose rotation channel samples accessor 1 at
/// the times of accessor 0 (two keys, 0 s and 1 s); `rotations` is the
/// second bufferView's JSON and `accessor` accessor 1's.
std::string head_gltf(const std::string& bin, const std::string& rotations, const std::string& accessor,
                      bool data_uri = true) {
    const std::string buffer = data_uri ? R"(, "uri": "data:application/octet-stream;base64,)" + base64(bin) + "\"" : "";
    return R"({"asset": {"version": "2.0"}, "nodes": [{"name": "head"}],
  "buffers": [{"byteLength": )" + std::to_string(bin.size()) + buffer + R"(}],
  "bufferViews": [{"buffer": 0, "byteLength": 8}, )" + rotations + R"(],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]}, )" +
           accessor + R"(],
  "animations": [{"samplers": [{"input": 0, "output": 1, "interpolation": "LINEAR"}],
                  "channels": [{"sampler": 0, "target": {"node": 0, "path": "rotation"}}]}]})";
}

/// Key times 0 and 1, then the identity and 90 degrees about z, as (x, y, z, w) floats.
std::string float_keys() {
    std::string bin;
    put(bin, 0.0f);
    put(bin, 1.0f);
    const float s = static_cast<float>(std::sqrt(0.5));
    for (const float v : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, s, s}) put(bin, v);
    return bin;
}

const std::string float_view = R"({"buffer": 0, "byteOffset": 8, "byteLength": 32})";
const std::string float_accessor = R"({"bufferView": 1, "componentType": 5126, "count": 2, "type": "VEC4"})";

/// A .glb of `json` and the BIN chunk `bin`, as the specification lays it out.
std::string glb(std::string json, std::string bin) {
    while (json.size() % 4) json += ' ';
    while (bin.size() % 4) bin += '\0';
    std::string out = "glTF";
    put(out, std::uint32_t{2});
    put(out, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
    put(out, static_cast<std::uint32_t>(json.size()));
    out += "JSON" + json;
    put(out, static_cast<std::uint32_t>(bin.size()));
    out += std::string("BIN\0", 4) + bin;
    return out;
}

void check_head(const document& d) {
    REQUIRE(d.tracks.size() == 1);
    const track& t = d.tracks[0];
    CHECK(t.name == "head");
    REQUIRE(t.keys.size() == 2);
    CHECK(t.keys[0].time == 0);
    CHECK(t.keys[1].time == 1);
    CHECK(same_rotation(t.keys[0].rotation, quat{1, 0, 0, 0}, 1e-7));
    CHECK(same_rotation(t.keys[1].rotation, quat{std::sqrt(0.5), 0, 0, std::sqrt(0.5)}, 1e-7));
}

}  // namespace

TEST_CASE("glTF: a rotation channel's keys, glTF's (x, y, z, w) as keyrot's (w, x, y, z)") {
    std::uint32_t one = 1;
    REQUIRE(*reinterpret_cast<unsigned char*>(&one) == 1);  // put() writes little-endian here
    check_head(read(head_gltf(float_keys(), float_view, float_accessor), format::gltf));
}

TEST_CASE("glTF: times on a rate read as k/fps, other times as the shortest decimals of their floats") {
    // Two keys' times as 32-bit floats; the second k/fps's nearest float, or not.
    const auto times_read = [](float second) {
        std::string bin;
        put(bin, 0.0f);
        put(bin, second);
        const float s = static_cast<float>(std::sqrt(0.5));
        for (const float v : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, s, s}) put(bin, v);
        std::string json = head_gltf(bin, float_view, float_accessor);
        json.replace(json.find(R"("max": [1])"), 10, R"("max": [)" + fmt::format("{}", second) + "]");
        return read(json, format::gltf).tracks.at(0).keys.at(1).time;
    };
    for (const double fps : {24.0, 25.0, 30.0, 60.0, 90.0, 30000.0 / 1001}) {
        CAPTURE(fps);
        CHECK(times_read(static_cast<float>(1 / fps)) == 1 / fps);  // the double k/fps, not the float's 0.0333333351
    }
    CHECK(times_read(static_cast<float>(7 / 30.0)) == 7 / 30.0);  // a first step of seven frames
    // On no rate: the float's shortest decimal, which reads back as the same float
    CHECK(times_read(0.12582215666770935f) == 0.12582216);
    // (a float a unit past 1/30's: no rate's)
    CHECK(times_read(std::nextafter(1.0f / 30, 1.0f)) == 0.03333334);
    CHECK(static_cast<float>(0.03333334) == std::nextafter(1.0f / 30, 1.0f));
}

TEST_CASE("glTF: a .glb with its BIN chunk reads as the .gltf with a data: URI") {
    check_head(read(glb(head_gltf(float_keys(), float_view, float_accessor, false), float_keys()), format::glb));
    const std::string whole = glb(head_gltf(float_keys(), float_view, float_accessor, false), float_keys());
    CHECK(error_of(whole.substr(0, whole.size() - 4), format::glb) ==
          "in: truncated GLB: the header says " + std::to_string(whole.size()) + " bytes, the file has " +
              std::to_string(whole.size() - 4));
}

TEST_CASE("glTF: normalised SHORT rotations are max(c / 32767, -1), and byteStride is followed") {
    // Each element: four SHORTs and four bytes of something else (stride 12).
    std::string bin;
    put(bin, 0.0f);
    put(bin, 1.0f);
    for (const std::int16_t c : {std::int16_t{0}, std::int16_t{0}, std::int16_t{0}, std::int16_t{32767}}) put(bin, c);
    bin += "pad!";
    for (const std::int16_t c : {std::int16_t{0}, std::int16_t{-32768}, std::int16_t{0}, std::int16_t{0}}) put(bin, c);  // -32768 is -1, as -32767 is
    bin += "pad!";
    const std::string view = R"({"buffer": 0, "byteOffset": 8, "byteLength": 24, "byteStride": 12})";
    const std::string accessor =
        R"({"bufferView": 1, "componentType": 5122, "normalized": true, "count": 2, "type": "VEC4"})";
    const std::string text = head_gltf(bin, view, accessor);
    std::istringstream in(text);
    gltf_file file = load_gltf(in, format::gltf, "in", ".", default_max_bytes);
    std::vector<double> values{7, 7, 7};  // (what it held before goes)
    read_accessor(file, gltf_json(std::size_t{1}), "rotation", {"VEC4", true}, values);
    CHECK(values == std::vector<double>{0, 0, 0, 1, 0, -1, 0, 0});
    const document d = read(text, format::gltf);
    REQUIRE(d.tracks.size() == 1);
    CHECK(same_rotation(d.tracks[0].keys[1].rotation, quat{0, 0, 1, 0}, 0));  // 180 degrees about y
    // Not normalised, SHORTs are no rotation glTF allows.
    CHECK(error_of(head_gltf(bin, view, R"({"bufferView": 1, "componentType": 5122, "count": 2, "type": "VEC4"})"),
                   format::gltf)
              .starts_with("in: animations[0].samplers[0].output"));
}

TEST_CASE("glTF: FLOAT components are the stored floats, packed or interleaved (byteStride)") {
    // Two rotations of four floats each, as (x, y, z, w), values no double
    // rounding could give back exactly; packed, then with 8 bytes of
    // something else after each (stride 24).
    const std::vector<float> stored{0.1f, -0.2f, 0.3f, 0.9f, -1e-30f, 3e38f, 0.5f, -0.75f};
    const auto element_bytes = [&](std::size_t i, const std::string& pad) {
        std::string bytes;
        for (std::size_t j = 0; j < 4; ++j) put(bytes, stored[4 * i + j]);
        return bytes + pad;
    };
    std::string times;
    put(times, 0.0f);
    put(times, 1.0f);
    const std::vector<double> widened(stored.begin(), stored.end());
    for (const std::string& pad : {std::string(), std::string("padding!")}) {
        CAPTURE(pad);
        const std::string bin = times + element_bytes(0, pad) + element_bytes(1, pad);
        const std::string stride = pad.empty() ? "" : R"(, "byteStride": 24)";
        const std::string view = R"({"buffer": 0, "byteOffset": 8, "byteLength": )" + std::to_string(bin.size() - 8) +
                                 stride + "}";
        std::istringstream in(head_gltf(bin, view, float_accessor));
        gltf_file file = load_gltf(in, format::gltf, "in", ".", default_max_bytes);
        std::vector<double> values(20, 7.0);  // (longer before: what it held goes)
        read_accessor(file, gltf_json(std::size_t{1}), "rotation", {"VEC4", true}, values);
        CHECK(values == widened);
    }
}

TEST_CASE("glTF: errors name the JSON path of what is wrong") {
    CHECK(error_of(head_gltf(float_keys(), float_view,
                             R"({"bufferView": 7, "componentType": 5126, "count": 2, "type": "VEC4"})"),
                   format::gltf) == "in: animations[0].samplers[0].output: accessor 1: 7: expected an index into bufferViews (0 to 1)");
    CHECK(error_of(head_gltf(float_keys(), R"({"buffer": 0, "byteOffset": 8, "byteLength": 40})", float_accessor),
                   format::gltf) == "in: bufferViews[1]: bytes 8 to 48 read past the end of buffer 0 (40 bytes)");
}

TEST_CASE("glTF: a .glb written by open_table reads back, within 32-bit floats") {
    const scratch s;
    const std::string path = (s.dir / "out.glb").string();
    std::ostringstream out, err;
    warnings warn(err, "in");
    write_options w;
    w.representation = rep::quat;
    table_info info;
    info.named = true;
    const auto table = open_table(format::glb, path, out, info, w, warn);
    table->begin_track("neck", channels{}, track_interpolation{});
    std::vector<quat> written;
    for (int i = 0; i <= 24; ++i) {
        const double half = 0.5 * (i * 7.5) * std::acos(-1.0) / 180;  // 7.5 degrees a frame about x
        written.push_back({std::cos(half), std::sin(half), 0, 0});
        table->row(table_row{{i / 24.0, static_cast<double>(i), written.back(), std::nullopt, std::nullopt}});
    }
    table->finish();
    const document d = read(scratch::read(path), format::glb);
    REQUIRE(d.tracks.size() == 1);
    CHECK(d.tracks[0].name == "neck");
    REQUIRE(d.tracks[0].keys.size() == written.size());
    for (std::size_t i = 0; i < written.size(); ++i) {
        CHECK(d.tracks[0].keys[i].time == doctest::Approx(static_cast<double>(i) / 24).epsilon(1e-7));
        CHECK(same_rotation(d.tracks[0].keys[i].rotation, written[i], 1e-7));
    }
}

}  // namespace keyrot::test
