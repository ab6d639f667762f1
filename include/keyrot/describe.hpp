#pragma once
// What `keyrot info` tells about a track.
#include <string>
#include <vector>

#include "keyrot/track.hpp"

namespace keyrot {

struct segment_info {
    double angle_deg = 0;        ///< rotation from key i to key i+1, the short way
    double speed_deg_s = 0;      ///< mean angular speed
    bool direct_long_way = false;  ///< the keys as written lie in opposite hemispheres
};

struct track_info {
    std::string name;
    std::size_t keys = 0;
    double start = 0, end = 0;           ///< seconds
    std::vector<rep> given_as;           ///< the representations read, in order of first use
    std::vector<segment_info> segments;  ///< one per pair of neighbouring keys
    std::vector<std::size_t> flipped;        ///< keys negated by --path shortest
    std::vector<std::size_t> renormalised;   ///< keys whose norm was off by > tol::unit_norm
    std::vector<std::size_t> near_gimbal;    ///< Euler keys within near_gimbal_deg of gimbal lock
    /// Some key was given with a sign (not a matrix, whose quaternion's
    /// sign is keyrot's choice): only then do `flipped` and
    /// `direct_long_way` say something about the input.
    bool signed_keys = false;
};

/// Euler keys whose middle angle is this close to its singular value are reported.
inline constexpr double near_gimbal_deg = 1;

/// What `keyrot info` prints of a track: a track of two keys, the identity
/// at 0 s and 90 degrees about z at 1 s, has one segment of 90 degrees at
/// 90 degrees per second.
track_info describe(const track& t);

}  // namespace keyrot
