// SPDX-License-Identifier: MIT
#pragma once
// A glTF 2.0 accessor's elements, decoded as the specification says: FLOAT
// components as stored, normalised integers, byteStride, sparse substitution.
#include <string>
#include <string_view>
#include <vector>

#include "io/gltf/gltf_file.hpp"

namespace keyrot {

/// What a reader takes from an accessor: its type ("SCALAR", "VEC3",
/// "VEC4") and whether normalised BYTE, UNSIGNED_BYTE, SHORT and
/// UNSIGNED_SHORT components are read (as well as FLOAT).
struct accessor_kind {
    std::string_view type;
    bool normalized_integers = false;
};

/// An accessor's count, and how many of its elements the file stores: all
/// with a bufferView; else its sparse substitutes, the rest being 0. So a
/// reader can check what the count claims before read_accessor allocates it.
struct accessor_size {
    std::size_t count, stored;
};
accessor_size size_of_accessor(const gltf_file& file, const gltf_json& index, const std::string& path);

/// The elements of accessor `index` (a JSON value, for its checks), their
/// components one after another, decoded as the specification says
/// (byteStride, normalised integers, sparse substitution). `path` names what
/// refers to it, for messages: "walk.glb: animations[0].samplers[2].output:
/// accessor 14 reads past the end of buffer 0".
/// They go into `values`, whose memory is reused.
void read_accessor(gltf_file& file, const gltf_json& index, const std::string& path, const accessor_kind& kind,
                   std::vector<double>& values);

}  // namespace keyrot
