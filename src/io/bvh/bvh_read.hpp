// SPDX-License-Identifier: MIT
#pragma once
// BVH motion capture: a joint hierarchy, then one line of channel values
// per frame. Each joint with channels is a track: its rotation channels
// the intrinsic Euler sequence of their order, its position channels the
// translation.
#include <array>
#include <istream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/common/interface.hpp"

namespace keyrot {

/// A joint of the hierarchy that has channels, in file order.
struct bvh_joint {
    std::string name;  ///< as written after ROOT or JOINT
    std::size_t line = 0;
    /// The CHANNELS names in order ("Xposition", "Zrotation", ...).
    std::vector<std::string> channels;
    /// Per channel: 0..2 for X/Y/Z position, 3..5 for X/Y/Z rotation.
    std::vector<int> kinds;
    /// The rotation channels' axes in order, completed with the axes they
    /// leave out (at angle 0): "ZXY" for Zrotation Xrotation Yrotation.
    euler_seq euler;
    bool positions = false;  ///< some position channel
};

/// A ROOT, JOINT or End Site of the hierarchy, in file order.
struct bvh_node {
    std::string name;  ///< an End Site's: its joint's name and "_End"
    std::optional<std::size_t> parent;
    vec3 offset;
    std::optional<std::size_t> joint;  ///< its index in bvh_source::joints, if it has channels
};

/// A BVH file's hierarchy, as a BVH output of it keeps it.
struct bvh_source {
    std::string hierarchy;  ///< the bytes before the MOTION line, as they were
    std::string newline;    ///< "\r\n" where the file has them, else "\n"
    std::vector<bvh_node> nodes;
    std::vector<bvh_joint> joints;
    double frame_time = 0;        ///< as written
    std::string frame_time_text;  ///< as written, to the digit ("0.0083333")
    double fps = 0;         ///< the rate keys count at (README: "BVH")
    std::size_t frames = 0;
};

/// The keys of a BVH file, joint after joint: key i of each joint is frame
/// i, at the file's rate (its settings' key_fps). Throws input_error naming
/// the file and line: "take.bvh:40: expected 69 values (the hierarchy's
/// channels), got 68".
std::unique_ptr<key_reader> make_bvh_reader(std::istream& in, const read_options& ro);

/// The hierarchy and the motion's header, without reading the frames.
std::shared_ptr<bvh_source> read_bvh_source(std::istream& in, const read_options& ro);

}  // namespace keyrot
