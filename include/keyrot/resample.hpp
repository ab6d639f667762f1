// SPDX-License-Identifier: MIT
#pragma once
// The frame grid: every frame k with k/fps inside a track's key range,
// produced as the track's keys arrive.
#include <deque>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "keyrot/interpolate.hpp"
#include "keyrot/track.hpp"

namespace keyrot {

struct resample_options {
    double fps = 24;
    method how = method::slerp;
    path way = path::shortest;
    /// At most this many frames per track (116 hours at 24 fps), so that a
    /// typo in a time fails at once instead of writing for hours.
    double max_frames = 1e7;
    /// How translations, scales and morph weights are interpolated, where
    /// not as `how` says: step holds, cubicspline is Hermite, any other
    /// method is linear.
    std::optional<method> translation_how = std::nullopt, scale_how = std::nullopt, weights_how = std::nullopt;
    /// The relative rounding of the key times as stored (2^-24 for glTF's
    /// 32-bit floats): a frame that close to a key is at it, beyond the
    /// grid's own tolerance of 1e-9 frame.
    double time_rounding = 0;
    /// Each frame's angular velocity and acceleration (segment_curve::rates),
    /// in the body frame or the fixed one. At a key, where a method's
    /// derivative may jump, the outgoing segment's (the incoming one's at the last key).
    bool velocity = false, acceleration = false;
    motion_frame rates_frame = motion_frame::body;
};

/// Where frames go as they are made.
using frame_sink = std::function<void(const sample&)>;

/// Where slerp and squad frames may go before their rotations are worked
/// out: a consumer that works them out itself, later and on other threads
/// (the thread that makes the frames is the one the others wait for). It
/// takes a segment's keys, then each of that segment's frames: its rotation
/// is arc_curve(keys).at(segment_fraction(t0, t1, time)), the bits resample
/// would give. Such frames skip the sign chain (each frame's quaternion
/// nearest the one before), which needs every rotation in order: only a
/// consumer whose output is the same for q and -q may take them.
class arc_frame_sink {
public:
    virtual void keys(const arc_keys& k) = 0;
    virtual void frame(double frame, double time) = 0;

protected:
    ~arc_frame_sink() = default;
};

/// The first and last frame of the grid for keys from `first` to `last`
/// seconds: a frame within tolerance of a key counts as at it.
std::pair<double, double> frame_span(double first, double last, const resample_options& opts);

/// A track that would have more frames than resample_options::max_frames.
struct frame_limit_error : input_error {
    using input_error::input_error;
};

/// Throws input_error (naming the key, in `source`) when a track whose keys
/// run from `first` to `last` would have more than opts.max_frames frames
/// (frame_limit_error) or frame numbers beyond 2^53: keys from 0 s to 1e6 s
/// at 24 fps (24 million frames) are refused under the default limit.
void check_frame_range(const key& first, const key& last, const std::string& track_name,
                       const resample_options& opts, const std::string& source);

/// A value of a channel beside the rotation (a translation's or scale's,
/// or morph weights) between keys `a` and `b` of times `ta` < `tb` at
/// `time`, with the tangents `out_a` (a's) and `in_b` (b's) for
/// cubicspline: step holds a, cubicspline is hermite(), any other method is
/// linear, component-wise.
vec3 channel_between(method how, double ta, const vec3& a, const vec3& out_a, double tb, const vec3& b, const vec3& in_b,
                     double time);
morph_weights channel_between(method how, double ta, const morph_weights& a, const morph_weights& out_a, double tb,
                              const morph_weights& b, const morph_weights& in_b, double time);

/// One channel of a track beside its rotation (its translation, scale or
/// morph weights) as its keys arrive: as channel_between plays it between
/// the keys that carry one, held before the first and after the last of them.
template <class V>
class value_channel {
public:
    /// `how` as resample_options::translation_how; `expected`: some key of
    /// the track carries this channel (frames then wait for its key after them).
    value_channel(const resample_options& opts, method how, bool expected);
    /// Times strictly increasing. `in`, `out`: cubicspline's tangents.
    void add(double time, V value, V in, V out);
    /// Sets `value` to the channel at a frame's `time` and returns true, or
    /// returns false while the key at or after `time` has not arrived (unless
    /// `end`: no more keys come). Frames ask in increasing time.
    bool at(double time, bool end, std::optional<V>& value);

private:
    struct channel_key {
        double time;
        V value, in, out;
    };

    resample_options opts_;
    method how_;
    bool expected_;
    std::vector<channel_key> keys_;  // the ones later frames may still need (a few: a deque costs more)
};

extern template class value_channel<vec3>;
extern template class value_channel<morph_weights>;

/// Resamples one track whose keys arrive one at a time: frames come out, in
/// order, as soon as the keys around them (and squad's look-ahead, and the
/// next translation, scale and weights key) are known. Frame k has time k / fps,
/// computed afresh, never accumulated. At a key time the rotation is that
/// key's; quaternion signs are continuous from frame to frame, starting
/// from the first key's sign (not where frames go to an arc_frame_sink,
/// whose consumer has no use for signs). The caller checks the range with
/// check_frame_range.
class track_resampler {
public:
    /// `carried`: the channels some key of the track carries. `arc_frames`:
    /// where a slerp or squad track's frames inside a segment that carry
    /// nothing but a rotation go instead of `emit` (none: every frame through `emit`).
    track_resampler(const resample_options& opts, const std::optional<euler_seq>& seq, channels carried,
                    frame_sink emit, arc_frame_sink* arc_frames = nullptr);
    /// Precondition: times strictly increasing (check_next).
    void add(const key& k);
    /// After the last key: the remaining frames.
    void finish();

private:
    void frames_of(const segment& s);
    void rated_frames_of(const segment& s, bool at_start);  // frames_of with velocity or acceleration
    void frames_until(double time, quat q);  // frames at a key time, up to `time` (within tolerance)
    void out(double frame, quat q);
    void rated_out(sample& s);
    /// Sets s's translation, scale and weights at its time; false while a key they need has not come.
    bool with_vectors(sample& s, bool end);
    void resolve_vectors(bool end);

    resample_options opts_;
    segment_builder builder_;
    frame_sink emit_;
    arc_frame_sink* arc_frames_;
    bool vectors_;  // a translation, scale or weights channel: frames wait in pending_
    bool started_ = false;
    double next_frame_ = 0;
    double last_time_ = 0;
    quat last_key_, previous_;
    segment popped_;  // the segment a key completes: one made for each key would be zeroed for each
    bool emitted_ = false;
    value_channel<vec3> translation_, scale_;
    value_channel<morph_weights> weights_;
    bool rates_;                   // velocity or acceleration
    motion rates_now_;             // the next frame's, in the body frame
    struct waiting {
        sample s;
        frame_rates rates;
    };
    std::deque<waiting> pending_;  // frames waiting for a translation, scale or weights key
    morph_weights weights_now_;    // what the frame handed over views
    frame_rates rates_out_;        // likewise
};

/// A whole track: check_frame_range, then every frame through emit. Keys at
/// 0 s (identity) and 1 s (90 degrees about z) at 4 fps, slerp: frames 0..4,
/// at 0, 22.5, 45, 67.5 and 90 degrees (the classic worked example of slerp's constant speed).
void resample(const track& t, const resample_options& opts, const std::string& source, const frame_sink& emit);

}  // namespace keyrot
