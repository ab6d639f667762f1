// SPDX-License-Identifier: MIT
#pragma once
// What both glTF writers share (the one that rewrites a glTF input, the one
// that makes a new file): the output's buffer with its bufferViews and
// accessors, 32-bit floats (and normalised 16-bit integers), and the file
// written at the end (a .glb, a .gltf with its .bin, or a .gltf with its
// buffer as a data: URI).
#include <cmath>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "io/common/output.hpp"
#include "io/common/spool.hpp"
#include "io/gltf/gltf_file.hpp"
#include "keyrot/error.hpp"
#include "keyrot/method.hpp"

namespace keyrot::detail {

/// `v` as glTF stores a FLOAT: 4 bytes, little-endian, appended to `out`.
void append_float(std::string& out, float v);

/// How an accessor's components are stored.
enum class component { float32, normalized_short };

/// Unit quaternion `q` (x, y, z, w) as glTF stores normalised SHORTs, 2
/// bytes each, little-endian, appended to `out`: of the integer vectors
/// next to q × 32767 (each component rounded down or up) whose length is
/// within 1 of 32767, the one nearest q in angle (of two as near, the
/// length nearer 32767). q × 32767 rounded to nearest is one of them, so
/// the one taken is within its angle: a component off by 0.5 / 32767 at
/// most, 2 asin(2 × 0.5 / 32767) = 0.0035°. And a quaternion read from
/// such integers and normalised is within 1 of them times 32767 in every
/// component, so it is stored as them again: a chain of conversions keeps
/// the integers.
void append_normalized_shorts(std::string& out, std::span<const double, 4> q);

/// `v` as a 32-bit float; an input_error at `where` ("walk.csv: track 'hip'") where it is too large for one.
float single(double v, const std::string& where, const char* what);

/// What is said of key times `a` and `b` that are one 32-bit float.
std::string one_float_apart(double a, double b);

/// As single(), with `where` called for the place only when there is an error to name it in.
float single_at(double v, const auto& where, const char* what) {
    const auto f = static_cast<float>(v);
    return std::isfinite(f) ? f : single(v, where(), what);
}

/// A key time `time` as a 32-bit float (single_at), after `before`: the
/// float of the key before it, given as `before_time`, or none for a first
/// key. An input_error at where() where the two are one float.
float time_after(double time, const float* before, double before_time, const auto& where) {
    const float f = single_at(time, where, "time");
    if (before && !(f > *before)) throw input_error(where(), one_float_apart(before_time, time));
    return f;
}

/// A sampler's interpolation for method `m`: STEP, CUBICSPLINE, or LINEAR.
const char* interpolation_name(method m);

/// The binary buffer of the output, its bufferViews and accessors appended
/// to `json`'s.
class buffer_builder {
public:
    /// `input`: the source of the rows, for messages.
    buffer_builder(gltf_json& json, std::string input) : source(std::move(input)), json_(json) {}
    std::string source;
    byte_spool bin;

    /// A bufferView of `data`, starting at an offset with the given remainder mod 4.
    std::size_t view(std::string_view data, std::size_t remainder = 0);
    /// A bufferView of what `data` holds.
    std::size_t view(byte_spool& data);
    /// A FLOAT accessor of `values` (`width` per element), with min and max
    /// when `bounds`: in a bufferView of its own, or in the shared one.
    std::size_t accessor(const std::vector<float>& values, std::size_t width, bool bounds);
    /// An accessor of `count` elements of `width` components `c`, stored as
    /// `data` holds them, with the bounds `lo` and `hi` where they are given:
    /// in a bufferView of its own, or in the shared one.
    std::size_t accessor(std::string_view data, std::size_t count, std::size_t width, component c,
                         const std::vector<float>& lo = {}, const std::vector<float>& hi = {});
    /// Until end_shared_view(), the accessors of values share one bufferView
    /// (nothing else may be added to the buffer meanwhile): a view each
    /// costs more JSON than a key's worth of data.
    void begin_shared_view() { shared_ = shared_view{}; }
    void end_shared_view();
    /// An accessor of `count` elements of `width` components `c` in
    /// bufferView `view`, with the bounds `lo` and `hi` where they are given.
    std::size_t accessor(std::size_t view, std::size_t count, std::size_t width, const std::vector<float>& lo,
                         const std::vector<float>& hi, component c = component::float32);

private:
    struct shared_view {
        std::optional<std::size_t> index;  // made with its first accessor (a bufferView is never empty)
        std::size_t start = 0;
    };
    std::size_t begin_view(std::size_t length, std::size_t remainder);
    std::optional<shared_view> shared_;
    std::size_t append(const char* name, gltf_json value);
    gltf_json& json_;
};

/// Writes `json` and the buffer `bin` as a file of format `f` (its
/// buffers[0] is the buffer): to `target` (a .gltf's buffer in the .bin
/// beside it; both written, then put in place as `commit` says, the .bin
/// first) or to `out` (a .gltf with its buffer as a data: URI). The
/// buffer goes out a block at a time.
void put_file(gltf_json& json, byte_spool& bin, format f, const std::optional<std::string>& target,
              commit_mode commit, std::ostream& out);

}  // namespace keyrot::detail
