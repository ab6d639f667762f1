// SPDX-License-Identifier: MIT
#pragma once
// Which tracks a glTF 2.0 file's animations make: one per animated node
// (and animation), merging its rotation, translation, scale and morph
// weights channels, named after the node.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "io/common/interface.hpp"
#include "io/gltf/gltf_file.hpp"

namespace keyrot {

/// Where a track of a glTF file came from: its animation and node, and the
/// channels (indices into the animation's channels) it merges.
struct gltf_track_origin {
    std::size_t animation = 0, node = 0;
    std::optional<std::size_t> rotation, translation, scale, weights;
    std::size_t targets = 0;  ///< with weights: the morph targets of the node's mesh
};

/// A track to be: a node's channels in one animation, and its name.
struct node_track {
    gltf_track_origin origin;
    std::string name;
};

/// Every track of the file (or of the one animation ro.animation names),
/// in the order of their nodes' first channels: named after the node
/// ("node<i>" when unnamed; "<name>.2" for a second node of one name),
/// prefixed "<animation>/" when several animations are read. Channels
/// other than rotation, translation, scale and weights are warned about
/// once and left out. Throws input_error naming the JSON path.
std::vector<node_track> tracks_of(const gltf_file& file, const read_options& ro, warnings& warn);

}  // namespace keyrot
