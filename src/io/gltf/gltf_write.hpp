// SPDX-License-Identifier: MIT
#pragma once
// glTF 2.0 output: the tracks' rows as animation samplers, in a new file
// (a node per track) or in place of a glTF input's own samplers, everything
// else of that file kept.
#include <array>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "io/gltf/gltf_read.hpp"
#include "keyrot/track.hpp"

namespace keyrot {

/// A node of a new file's skeleton (a BVH hierarchy), and the track that
/// animates it, if any.
struct gltf_node {
    std::string name;
    std::optional<std::size_t> parent;  ///< an earlier node
    vec3 translation;                   ///< its rest offset from the parent
    std::optional<std::size_t> track;
};

/// A glTF output of format `f` (gltf or glb) to `target` (a .gltf's buffer
/// to the .bin of the same name beside it, both put in place as `commit`
/// says only once both are written) or to `out` (a .gltf with its buffer
/// as a data: URI). With `source`, the glTF input the tracks were read from
/// (track i is its track i), that file is written with the samplers of the
/// channels keyrot read replaced and all else kept, at finish(); otherwise
/// a new file with the nodes of `skeleton` (none: a node per track) and one
/// animation, its data set aside in temporary files as the rows come.
/// Rotations, translations and scales are stored as 32-bit floats; with
/// `short_rotations` (--compact), LINEAR and STEP rotations as normalised
/// 16-bit integers. Throws keyrot::error.
std::unique_ptr<table_output> make_gltf_table(format f, const std::optional<std::string>& target, std::ostream& out,
                                              commit_mode commit, bool short_rotations,
                                              std::shared_ptr<gltf_source> source, std::vector<gltf_node> skeleton,
                                              warnings& warn);

/// make_gltf_table's new file (gltf_new_file.cpp).
std::unique_ptr<table_output> make_new_gltf_file(format f, const std::optional<std::string>& target, std::ostream& out,
                                                 commit_mode commit, bool short_rotations,
                                                 std::vector<gltf_node> skeleton, warnings& warn);

}  // namespace keyrot
