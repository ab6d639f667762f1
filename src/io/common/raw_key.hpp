// SPDX-License-Identifier: MIT
#pragma once
// Keys as the readers give them (raw_key: numbers as written in the file,
// in its units) and the one place where they become keyrot's keys
// (make_key), so that every input format is validated the same way.
#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "ground/warnings.hpp"
#include "keyrot/convert.hpp"
#include "keyrot/track.hpp"

namespace keyrot {

/// One key exactly as read: numbers in the file's units, not yet checked
/// beyond being finite. Quaternion values are in (w, x, y, z) order.
struct raw_key {
    location at;  ///< for errors
    std::optional<double> time, frame;
    rep kind = rep::quat;
    std::array<double, 16> values{};  ///< as many as `kind` needs
    std::optional<vec3> translation, scale;
    morph_weights weights;
    frame_rates rates;  ///< in the file's angle unit per second
    /// The unit the key's own names state (a column "angle_rad", a member
    /// "euler_rad"), over the settings'.
    std::optional<angle_unit> angles;
    std::string unknown;  ///< a JSON key's first field that keyrot does not read, if any
    std::optional<full_spline_key> spline;  ///< glTF CUBICSPLINE keys only

    /// Back to a default key in place, keeping the strings' storage: a reader
    /// that gives millions of keys fills one, where a fresh raw_key for each
    /// would be copied, tangents and all, once more.
    void reset() noexcept {
        at.line = 0;
        at.path.clear();
        time.reset(), frame.reset();
        kind = rep::quat;
        values.fill(0);
        translation.reset(), scale.reset();
        weights.clear();
        rates = {};
        angles.reset();
        unknown.clear();
        spline.reset();
    }
};

/// Settings that describe a document (flags, overridden by its own fields).
struct key_settings {
    angle_unit angles = angle_unit::degrees;
    /// The unit was typed (--radians): a file that states another gets one warning.
    bool angles_given = false;
    std::optional<euler_seq> euler;
    /// The rate frame numbers count at, where the file or the user states
    /// one; none: default_key_fps, assumed (and never written as stated).
    std::optional<double> key_fps;
    /// key_fps is the user's --key-fps, which no file's own rate overrides:
    /// it times every frame number, also beside a time that says otherwise
    /// (what an earlier command wrote from a rate it only assumed).
    bool key_fps_given = false;
    bool strict = false;
    std::optional<track_interpolation> interpolation = std::nullopt;  ///< a glTF track's own
    double frame_rate() const { return key_fps.value_or(default_key_fps); }
};

/// What a reader knows of a track before its keys.
struct raw_track {
    std::string name;  ///< empty for a file without tracks
    location at;  ///< the JSON track, or the CSV header, for errors
    key_settings settings;
};

/// One key converted and validated on its own: rotation to a unit
/// quaternion, frame to time. Throws input_error naming the key; warns once
/// per source about renormalised quaternions. A raw key of kind
/// rep::axis_angle with values {0, 0, 2, 90} (degrees) becomes rotation
/// {cos 45deg, 0, 0, sin 45deg}.
key make_key(const raw_key& raw, const key_settings& settings, warnings& warn);

/// A field of the input that keyrot does not read (a misspelt "translaton"):
/// one warning per source, or with strict settings an input_error at `where`.
void unknown_field(std::string_view name, const std::string& where, const key_settings& settings, warnings& warn);

/// A track built one key at a time (make_key, check_next, at least one
/// key), as a reader hands keys over, so that their raw values need not all
/// be held at once.
///
///     track_builder b("hip", {}, key_settings{});
///     b.add(raw_key_at_time_0, warn);
///     const track t = std::move(b).finish(warn);
class track_builder {
public:
    /// `at` and `settings` as raw_track's.
    track_builder(std::string name, location at, key_settings settings);
    /// make_key, and check_next against the key before.
    void add(const raw_key& raw, warnings& warn);
    /// Throws input_error for a track without keys.
    track finish(warnings& warn) &&;

private:
    location at_;
    key_settings settings_;
    track track_;
};

}  // namespace keyrot
