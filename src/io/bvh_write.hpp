#pragma once
// BVH output: the hierarchy of the BVH input kept as it was, then the rows
// of its tracks as frames, each joint's angles in its own channel order.
#include <memory>
#include <optional>
#include <ostream>
#include <string>

#include "io/bvh.hpp"
#include "io/io.hpp"

namespace keyrot {

/// The rows of the tracks of `source`'s joints (track i is joint i), held
/// until finish(), then written as a BVH file into `target` (replaced at
/// once) or `out`: Frame Time 1/info.fps, Euler angles continuous from frame
/// to frame (continuous_euler). Throws input_error, naming `source_name`,
/// for tracks with different frames.
std::unique_ptr<table_output> make_bvh_table(const std::optional<std::string>& target, std::ostream& out,
                                             std::shared_ptr<bvh_source> source, const table_info& info,
                                             const write_options& opts, warnings& warn);

}  // namespace keyrot
