#pragma once
// The frame grid: every frame k with k/fps inside a track's key range.
#include <functional>
#include <optional>

#include "keyrot/interpolate.hpp"
#include "keyrot/track.hpp"

namespace keyrot {

/// One output row: a resampled frame (frame = k) or a converted key.
struct sample {
    double time = 0;
    std::optional<double> frame;
    quat rotation;
    std::optional<vec3> translation;
    bool has_time = true;  ///< convert: the key gave a time (JSON writes "time" only then, if it has a frame)
};

struct resample_options {
    double fps = 24;
    method how = method::slerp;
    path way = path::shortest;
    /// At most this many frames per track (116 hours at 24 fps), so that a
    /// typo in a time fails at once instead of writing for hours.
    double max_frames = 1e7;
};

/// Calls emit for each frame k (ascending) with first key time <= k/fps <=
/// last key time, to within tol::grid_frames of a frame. time = k / fps is
/// computed afresh for each frame, never accumulated. At a key time the
/// rotation is that key's; quaternion signs are continuous from frame to
/// frame, starting from the first key's sign.
/// Throws input_error (naming the last key) when the range holds more than
/// opts.max_frames frames or frame numbers beyond 2^53.
void resample(const track& t, const resample_options& opts, const std::function<void(const sample&)>& emit);

}  // namespace keyrot
