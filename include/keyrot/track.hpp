// SPDX-License-Identifier: MIT
#pragma once
// Keys and tracks: what keyrot works on (key, with a unit quaternion, and
// track, its keys in time order), and the rows made of them (sample).
#include <algorithm>
#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "keyrot/convert.hpp"
#include "keyrot/error.hpp"
#include "keyrot/method.hpp"
#include "keyrot/quat.hpp"

namespace keyrot {

/// Where a key or track was read: a line (CSV, NDJSON) or a JSON key path.
/// Kept raw and formatted with the source's name only for a message.
struct location {
    std::size_t line = 0;
    std::string path;  ///< "tracks.hip.keys[3]"; empty for a line
};

/// "walk.csv:14", "walk.json: tracks.hip.keys[3]", or the source alone.
std::string where(const std::string& source, const location& at);
/// "walk.csv:14": line 14 of walk.csv (counted from 1; 0 is the source alone).
std::string where(std::string_view source, std::size_t line);
/// "walk.json: tracks.hip.keys[3]": a key path of a JSON or glTF source.
std::string where(std::string_view source, std::string_view path);

/// Morph target weights (glTF's `weights` channel), one per target of the
/// node's mesh; empty where a key carries none.
using morph_weights = std::vector<double>;

/// A glTF CUBICSPLINE key as its spline passes it: the rotation as stored
/// (not normalised), and the tangents, derivatives per second of the
/// quaternion's components (w, x, y, z), of the translation and of the scale.
struct spline_key {
    quat rotation{0, 0, 0, 0}, rotation_in{0, 0, 0, 0}, rotation_out{0, 0, 0, 0};
    vec3 translation_in, translation_out;
    vec3 scale_in, scale_out;
};

/// A CUBICSPLINE key whole: the spline_key, which a rotation's segments
/// carry (and copy often), and the tangents of the morph weights.
struct full_spline_key : spline_key {
    morph_weights weights_in = {}, weights_out = {};
};

/// How a file says a track is interpolated (glTF's samplers): the
/// rotation's method, and the translation's, scale's and weights' (step
/// holds, cubicspline is Hermite, any other is linear); and how precisely
/// it stores times.
struct track_interpolation {
    method rotation = method::slerp;
    method translation = method::slerp;
    method scale = method::slerp;
    method weights = method::slerp;
    double time_rounding = 0;  ///< as resample_options::time_rounding
    bool operator==(const track_interpolation&) const = default;
};

/// The rate frame numbers count at where neither the file nor the user
/// states one, whatever rate the output is resampled at.
inline constexpr double default_key_fps = 24;

/// A row's angular velocity and acceleration (radians per second, per
/// second squared), where asked for (resample --velocity) or read.
struct frame_rates {
    std::optional<vec3> velocity, acceleration;
    bool any() const { return velocity || acceleration; }
};

/// A rotation's values as a file gave them, in its angle unit: a
/// quaternion (w, x, y, z), an axis and angle, a rotation vector, or Euler
/// angles in the track's sequence, as key::given_as says.
struct given_rotation {
    std::array<double, 4> values{};
    angle_unit unit = angle_unit::degrees;
    /// The Euler angles in radians (for given_as rep::euler).
    std::array<double, 3> euler_radians() const noexcept {
        return {to_radians(values[0], unit), to_radians(values[1], unit), to_radians(values[2], unit)};
    }
};

struct key {
    location at;                  ///< where it was read, for errors
    double time = 0;              ///< seconds
    std::optional<double> frame;  ///< as given (the key's time, unless it also has a time)
    bool has_time = true;         ///< the input gave a time (not only a frame)
    quat rotation;                ///< unit
    std::optional<vec3> translation, scale;
    morph_weights weights;        ///< as many on every key of a track (check_next)
    rep given_as = rep::quat;
    /// The rotation as given, but for matrices: the Euler angles --method
    /// euler interpolates, the values a round trip writes back (reduce's kept
    /// keys, an output in the representation they were given in).
    std::optional<given_rotation> given;
    bool renormalised = false;  ///< input norm differed from 1 by > tol::unit_norm
    /// glTF CUBICSPLINE keys only (held apart: keys are copied often, and most have none).
    std::shared_ptr<const full_spline_key> spline;
    /// As read, in radians (a frame of resample --velocity); held apart as the spline.
    std::shared_ptr<const frame_rates> rates;
};

struct track {
    std::string name;
    std::optional<euler_seq> euler;  ///< the sequence in force for this track
    std::vector<key> keys;
    /// The rate frame numbers count at, where the file or the user states
    /// one; none: default_key_fps, assumed (and never written as stated).
    std::optional<double> key_fps;
    std::optional<track_interpolation> interpolation = std::nullopt;  ///< the file's own, where it states one
    /// The rate its keys' frame numbers count at.
    double frame_rate() const { return key_fps.value_or(default_key_fps); }
};

/// The optional channels beside the rotation that some key of a track
/// carries, and so its rows: a track with a translation writes tx ty tz on
/// every row.
struct channels {
    bool translation = false, scale = false;
    std::size_t weights = 0;  ///< the most morph weights a key carries
    bool operator==(const channels&) const = default;
    channels& operator|=(const channels& o) {
        translation = translation || o.translation, scale = scale || o.scale;
        weights = std::max(weights, o.weights);
        return *this;
    }
    bool any() const { return translation || scale || weights; }
};

/// The channels key `k` carries.
inline channels channels_of(const key& k) { return {k.translation.has_value(), k.scale.has_value(), k.weights.size()}; }

/// A track's value at a time: what the resampler makes of its keys (frame
/// k), or a key as it is.
struct sample {
    double time = 0;
    std::optional<double> frame;
    quat rotation;
    std::optional<vec3> translation;
    std::optional<vec3> scale = std::nullopt;
    /// The morph weights, held by whoever hands the sample over, valid
    /// during that call: a sample stays trivially copyable, so the frames
    /// of the everyday track (which has none) cost no more to pass around.
    std::span<const double> weights = {};
    /// The angular velocity and acceleration, where asked for, held as the weights are.
    const frame_rates* rates = nullptr;
};
static_assert(std::is_trivially_copyable_v<sample>);

/// Throws input_error unless `next` may follow `previous` in a track:
/// strictly after it, and with as many morph weights (none, or one per
/// target, on every key). Keys at 0 s then 0 s give "walk.csv:3: time 0 s
/// is not after the previous key's 0 s: expected strictly increasing times".
/// (Inline: it is asked of every key.)
inline void check_next(const key& previous, const key& next, const std::string& source);

/// check_next's error, out of line as it is rare.
[[noreturn, gnu::cold]] void not_next(const key& previous, const key& next, const std::string& source);

inline void check_next(const key& previous, const key& next, const std::string& source) {
    if (!(next.time > previous.time) || next.weights.size() != previous.weights.size()) [[unlikely]]
        not_next(previous, next, source);
}

}  // namespace keyrot
