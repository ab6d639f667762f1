// SPDX-License-Identifier: MIT
#pragma once
// glTF 2.0 animations as tracks: one track per animated node (and
// animation), its rotation, translation, scale and morph weights channels
// merged on one list of key times, interpolated as their samplers say.
#include <istream>
#include <memory>
#include <string>

#include "io/common/interface.hpp"
#include "io/gltf/gltf_file.hpp"
#include "io/gltf/gltf_tracks.hpp"

namespace keyrot {

/// A glTF input, kept for a glTF output that rewrites it: the file, and
/// the document's tracks (their names and origins), in their order.
struct gltf_source {
    gltf_file file;
    std::vector<node_track> tracks;
};

/// The keys of a glTF file (`f`: gltf or glb; relative buffer URIs from the
/// directory of ro.source), track after track: every animation's, or the
/// one ro.animation names. A track is a node's rotation, translation,
/// scale and weights channels in one animation, named after the node ("node<i>" when
/// unnamed), prefixed "<animation>/" when several animations are read.
/// Where the channels are keyed at different times, each gets a key at the
/// other's times too, its value on its own curve there (so the curve is the
/// same). A track's settings() state its samplers' interpolation. Throws
/// input_error naming the JSON path: "walk.glb: animations[0].samplers[2]
/// .output: accessor 14 ...".
std::unique_ptr<key_reader> make_gltf_reader(std::istream& in, format f, const read_options& ro, warnings& warn);

/// The file, and the origin of each track make_gltf_reader gives, for a
/// glTF output that rewrites it, and for the readers of later passes.
std::shared_ptr<gltf_source> read_gltf_source(std::istream& in, format f, const read_options& ro, warnings& warn);
/// The keys of a file read_gltf_source loaded, as make_gltf_reader gives
/// them: each pass over a glTF input reads it from memory, and the file
/// once. The reader shares `loaded` (its buffers are decoded on first use).
std::unique_ptr<key_reader> make_gltf_reader(std::shared_ptr<gltf_source> loaded, const read_options& ro,
                                             warnings& warn);

/// The bytes of the file's buffers, which its keys are read from, each
/// read now if it was not yet. Throws input_error for one that cannot be.
std::size_t read_buffers(gltf_source& loaded);

/// A reader of each track's keys alone, as make_gltf_reader gives them, in
/// their order: tracks so read apart may be read on threads of their own at
/// once. What the file's tracks warn of was said when it was loaded. Every
/// buffer of the file is read first (input_error for one that cannot be).
std::vector<std::unique_ptr<key_reader>> make_gltf_track_readers(const std::shared_ptr<gltf_source>& loaded,
                                                                  const read_options& ro);

}  // namespace keyrot
