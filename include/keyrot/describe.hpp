#pragma once
// What `keyrot info` tells about a track, learnt a key at a time.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

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
    key_list flipped;       ///< keys negated by --path shortest
    key_list renormalised;  ///< keys whose norm was off by > tol::unit_norm
    key_list near_gimbal;   ///< Euler keys within near_gimbal_deg of gimbal lock
    /// Some key was given with a sign (not a matrix, whose quaternion's
    /// sign is keyrot's choice): only then do `flipped` and
    /// `direct_long_way` say something about the input.
    bool signed_keys = false;
    /// Keys are evenly spaced: the gaps differ by no more than rounding.
    bool even() const { return keys > 1 && longest_gap - shortest_gap <= 1e-9 * std::max(1.0, std::fabs(end)); }
};

/// Euler keys whose middle angle is this close to its singular value are reported.
inline constexpr double near_gimbal_deg = 1;

/// A track described as its keys arrive, in time order, in constant
/// memory unless every segment is kept.
class track_describer {
public:
    /// `euler`: the track's sequence; `segments`: keep every segment.
    track_describer(std::string name, std::optional<euler_seq> euler, bool segments);
    void add(const key& k);
    const track_info& info() const noexcept { return info_; }

private:
    std::optional<euler_seq> euler_;
    bool keep_segments_;
    track_info info_;
    quat previous_{};  ///< the previous key's rotation
    double previous_time_ = 0;
    quat aligned_{};  ///< the previous key as --path shortest plays it
};

/// What `keyrot info` prints of a track, every segment kept: a track of two
/// keys, the identity at 0 s and 90 degrees about z at 1 s, has one segment
/// of 90 degrees at 90 degrees per second.
track_info describe(const track& t);

}  // namespace keyrot
