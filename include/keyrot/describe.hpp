// SPDX-License-Identifier: MIT
#pragma once
// What `keyrot info` tells about a track, learnt a key at a time.
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "keyrot/interpolate.hpp"
#include "keyrot/track.hpp"

namespace keyrot {

struct segment_info {
    double angle_deg = 0;        ///< rotation from key i to key i+1, the short way
    double speed_deg_s = 0;      ///< mean angular speed
    bool direct_long_way = false;  ///< the keys as written lie in opposite hemispheres
};

/// Indices of keys with something to say of them: how many, and the first
/// few (a long track may have thousands).
struct key_list {
    static constexpr std::size_t listed = 10;
    std::size_t count = 0;
    std::vector<std::size_t> first;  ///< the first `listed`
    void add(std::size_t i) {
        if (count++ < listed) first.push_back(i);
    }
};

/// Where a track's curve is fastest, or accelerates most.
struct peak {
    double value = 0;                      ///< deg/s, or deg/s^2
    double time = 0;                       ///< seconds
    std::size_t from = 0;  ///< the index of the segment's first key (the next is the segment's last)
    /// The segment's keys' frame numbers, where they have them.
    std::optional<double> frame = std::nullopt, frame_to = std::nullopt;
    double angle_deg = 0;  ///< the angle the segment turns along the curve
};

/// The speed of a track's curve under a method: its largest angular speed
/// and acceleration, its mean speed, and the segments far faster than
/// those around them.
struct speed_info {
    method how = method::slerp;
    peak fastest, most_accelerated;
    double mean = 0;           ///< deg/s, over the track's time
    std::vector<peak> spikes;  ///< the first key_list::listed, in time order
    std::size_t spike_count = 0;
};

/// A segment is a spike (a flip, swapped joints or a marker drop in a
/// captured take) where its largest speed is so many times the median of
/// the largest speeds of the spike_window segments around it (the segment
/// in the middle; fewer at a track's ends; taken afresh every
/// spike_median_every segments, as it changes slowly): judged against the
/// track's own motion, so a pop of 8 degrees in a take that moves 1 degree a
/// second is one, and a steady fast spin is none; and where it turns more
/// than spike_least_deg, as less would not show.
inline constexpr double spike_times_median = 10, spike_least_deg = 1;
inline constexpr std::size_t spike_window = 65, spike_median_every = 16;

struct track_info {
    std::string name;
    std::size_t keys = 0;
    double start = 0, end = 0;  ///< seconds
    /// The shortest and the longest time between neighbouring keys.
    double shortest_gap = std::numeric_limits<double>::infinity(), longest_gap = 0;
    std::vector<rep> given_as;  ///< the representations read, in order of first use
    /// The segment of the largest angle (the first of equals), and the index of its first key.
    std::optional<segment_info> largest;
    std::size_t largest_from = 0;
    double largest_start = 0, largest_end = 0;  ///< its keys' times
    /// Every segment, one per pair of neighbouring keys, where asked for.
    std::vector<segment_info> segments;
    /// Quaternion keys given with the other sign than the quaternion key
    /// before (--path shortest turns them back): each against its
    /// neighbour, so one key given flipped lists that key and the next.
    key_list flipped;
    key_list renormalised;  ///< keys whose norm was off by > tol::unit_norm
    key_list near_gimbal;   ///< Euler keys within near_gimbal_deg of gimbal lock
    /// Some key was given with a sign (not a matrix, whose quaternion's
    /// sign is keyrot's choice): only then does `direct_long_way` say
    /// something about the input.
    bool signed_keys = false;
    /// Some key was given as a quaternion: only then does `flipped` (Euler
    /// angles past +-180 degrees, or an axis-angle past 180, change the
    /// sign of the quaternion keyrot makes of them, which the file never had).
    bool quaternion_keys = false;
    /// The curve's speed (two keys or more; once finish() has come).
    std::optional<speed_info> speed;
    /// Keys are evenly spaced: the gaps differ by no more than rounding.
    bool even() const { return keys > 1 && longest_gap - shortest_gap <= 1e-9 * std::max(1.0, std::fabs(end)); }
};

/// Euler keys whose middle angle is this close to its singular value are reported.
inline constexpr double near_gimbal_deg = 1;

/// A track described as its keys arrive, in time order, in constant memory
/// unless every segment is kept (--segments); cubic holds a stretch of keys,
/// as resample does.
class track_describer {
public:
    /// `euler`: the track's sequence; `segments`: keep every segment; the
    /// speeds are those of the curve `how` and `way` play: the largest of
    /// five points of each segment, but slerp's and step's, one speed a
    /// segment, from its keys alone.
    /// Throws option_error for method::euler without a sequence.
    track_describer(std::string name, std::optional<euler_seq> euler, bool segments, method how = method::slerp,
                    path way = path::shortest);
    void add(const key& k);
    /// After the last key: the speeds. Throws spline_error as segment_builder::pop.
    void finish();
    const track_info& info() const noexcept { return info_; }

private:
    void measure(const segment& s);            // a segment of a curve whose speed changes
    void settle(const peak& fastest, double angle);  // a segment's fastest point and the angle it turns
    // spikes? the segments not yet judged before `end`, against window_'s median (afresh if `last`)
    void judge_until(std::size_t end, bool last);
    segment_builder builder_;
    bool steady_;  // slerp or step: one speed a segment, from the keys alone
    path way_;
    segment_info last_segment_;
    std::optional<double> previous_frame_;
    std::deque<peak> window_;  // the latest segments' fastest points, up to spike_window
    std::size_t dropped_ = 0;  // segments gone from the front of window_
    std::size_t segments_seen() const noexcept { return dropped_ + window_.size(); }  // the next one's index
    std::size_t judged_ = 0;   // segments judged (each once, in order)
    double median_ = 0;        // of window_, taken since_median_ segments ago
    std::size_t since_median_ = spike_median_every;
    double speed_time_ = 0;    // the integral of the speed over the segments measured, deg
    std::deque<std::optional<double>> frames_;  // the frame numbers of the keys no segment has begun at yet
    std::optional<euler_seq> euler_;
    bool keep_segments_;
    track_info info_;
    quat previous_{};  ///< the previous key's rotation
    double previous_time_ = 0;
    rep previous_given_as_ = rep::quat;
};

/// What `keyrot info` prints of a track, every segment kept, its speeds
/// by slerp: a track of two keys, the identity at 0 s and 90 degrees about
/// z at 1 s, has one segment of 90 degrees at 90 degrees per second.
track_info describe(const track& t);

}  // namespace keyrot
