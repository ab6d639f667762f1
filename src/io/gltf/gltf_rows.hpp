// SPDX-License-Identifier: MIT
#pragma once
// A rewritten glTF file's tracks, gathered row by row as the file stores
// them (gltf_write.cpp's rewritten table), and a track gathered apart from
// the others, on a thread of its own. Internal to io/gltf.
#include <exception>
#include <span>
#include <string>
#include <vector>

#include "io/common/interface.hpp"
#include "io/gltf/gltf_buffer.hpp"

namespace keyrot::detail {

/// The channels of a node keyrot writes, by their glTF target path.
enum class gltf_path { rotation, translation, scale, weights };

/// A channel of a track as the file stores it, made row by row (on the
/// thread that makes the rows): its key times and values as 32-bit floats,
/// or a short rotation's normalised 16-bit integers. What cannot be stored
/// (a value beyond a float, two times one float) is kept, to be said when
/// the channel's sampler is added, in the order of the file's channels: its
/// times' first, then its values'.
struct stored_channel {
    explicit stored_channel(std::size_t values_a_key = 0) : width(values_a_key) {}
    std::size_t width;  // values a key: 4 for a rotation, 3, or a weight per morph target
    std::vector<float> times, values;  // per key: width values; CUBICSPLINE: in-tangent, value, out-tangent
    std::string shorts;                // a short rotation's values
    double last_time = 0;              // the last key's, as the row gave it
    std::exception_ptr bad_time, bad_value;

    /// A key at `time`, whose values `put` puts (`where` names the track in a message).
    template <class Where, class Put>
    void add(double time, const Where& where, const Put& put) {
        if (bad_time) return;
        try {
            times.push_back(time_after(time, times.empty() ? nullptr : &times.back(), last_time, where));
            last_time = time;
        } catch (const input_error&) {
            bad_time = std::current_exception();
            return;
        }
        if (bad_value) return;
        try {
            put();
        } catch (const input_error&) {
            bad_value = std::current_exception();
        }
    }
    void put(std::span<const double> v, const auto& where, const char* what) {
        for (const double x : v) values.push_back(single_at(x, where, what));
    }
};

/// One track's rows as a glTF file stores them.
struct stored_track {
    std::string name;
    track_interpolation how;  // slerp is written LINEAR, step STEP, cubicspline CUBICSPLINE
    std::size_t rows = 0;
    stored_channel rotation{4}, translation{3}, scale{3}, weights;

    const stored_channel& channel(gltf_path path) const {
        switch (path) {
            case gltf_path::translation: return translation;
            case gltf_path::scale: return scale;
            case gltf_path::weights: return weights;
            case gltf_path::rotation: break;
        }
        return rotation;
    }
    method how_of(gltf_path path) const {
        switch (path) {
            case gltf_path::translation: return how.translation;
            case gltf_path::scale: return how.scale;
            case gltf_path::weights: return how.weights;
            case gltf_path::rotation: break;
        }
        return how.rotation;
    }
};

/// Tracks' rows gathered as a glTF file stores them, row by row (with
/// `short_rotations`, a LINEAR or STEP rotation as normalised 16-bit
/// integers); `source` names the rows in messages.
class gathered_rows : public table_output {
public:
    gathered_rows(bool short_rotations, std::string source)
        : short_rotations_(short_rotations), source_(std::move(source)) {}
    void begin_track(const std::string& name, channels, const track_interpolation& written) override;
    void row(const table_row& s) override;

protected:
    bool short_rotations_;
    std::string source_;
    std::vector<stored_track> tracks_;
};

/// A track's rows gathered apart from the others' (track_apart), put
/// after the ones before it in `tracks` at finish().
class gathered_apart final : public gathered_rows {
public:
    gathered_apart(bool short_rotations, std::string source, std::vector<stored_track>& tracks)
        : gathered_rows(short_rotations, std::move(source)), tracks_put_(tracks) {}
    void finish() override;

private:
    std::vector<stored_track>& tracks_put_;
};

}  // namespace keyrot::detail
