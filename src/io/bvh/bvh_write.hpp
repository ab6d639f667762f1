#pragma once
// BVH output: the hierarchy of the BVH input kept as it was, then the rows
// of its joints' tracks as frame lines, each joint's angles in its own
// channel order.
#include <deque>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "io/bvh/bvh_read.hpp"
#include "io/common/interface.hpp"

namespace keyrot {

namespace detail {
class chunked_output;
}

/// A BVH file of `source`'s hierarchy, written frame by frame into `target`
/// (replaced at finish()) or `out`: 'Frames: frames', 'Frame Time:
/// frame_time', then a line per frame once every joint's row of it has
/// come; Euler angles continuous from frame to frame (continuous_euler).
/// Rows of one joint come in order, the joints' rows in any interleaving.
class bvh_output {
public:
    bvh_output(const std::optional<std::string>& target, std::ostream& out, std::shared_ptr<const bvh_source> source,
               std::size_t frames, double frame_time, const write_options& opts);
    bvh_output(const bvh_output&) = delete;
    bvh_output& operator=(const bvh_output&) = delete;
    ~bvh_output();
    /// Row `s` of the track of joint `joint` (an index into source->joints).
    void row(std::size_t joint, const sample& s);
    /// Throws keyrot::error unless the rows made exactly the frames stated.
    void finish();

private:
    /// What BVH keeps of a row.
    struct frame_row {
        double time;
        quat rotation;
        vec3 translation;  // zero where the row has none
    };
    void write_frame();

    std::unique_ptr<detail::chunked_output> sink_;
    std::shared_ptr<const bvh_source> source_;
    std::size_t frames_, written_ = 0;
    write_options opts_;
    std::vector<std::deque<frame_row>> waiting_;   // per joint, the rows of frames not yet written
    std::size_t complete_ = 0;                     // joints with a row waiting
    std::vector<std::array<double, 3>> previous_;  // per joint, the last frame's angles
};

}  // namespace keyrot
