// SPDX-License-Identifier: MIT
#pragma once
// BVH output: the hierarchy of the BVH input kept as it was, then the rows
// of its joints' tracks as frame lines, each joint's angles in its own
// channel order.
#include <memory>
#include <optional>
#include <ostream>
#include <string>

#include "io/bvh/bvh_read.hpp"
#include "io/bvh/track_store.hpp"
#include "io/common/interface.hpp"

namespace keyrot {

namespace detail {
class chunked_output;
}

/// A BVH file of `source`'s hierarchy, a table like the others: its
/// tracks, one per joint in the hierarchy's order, come track after track,
/// and at finish() it writes 'Frames: N', 'Frame Time: 1/fps' (the
/// input's Frame Time as it was written, where fps is none or its rate), then
/// a line per frame (each joint's row of it) into `target` (replaced at
/// finish()) or `out`. Each row brings its joint's Euler angles (in
/// degrees, in the joint's sequence: table_row::own), which the caller
/// chooses (the input's own at its frames, continuous between). The rows
/// wait in a track_store meanwhile, so memory does not grow with the take.
class bvh_output final : public table_output {
public:
    bvh_output(const std::optional<std::string>& target, std::ostream& out, std::shared_ptr<const bvh_source> source,
               std::optional<double> fps, const write_options& opts);
    bvh_output(const bvh_output&) = delete;
    bvh_output& operator=(const bvh_output&) = delete;
    ~bvh_output() override;
    /// The next joint's track. Throws keyrot::error past the last joint.
    void begin_track(const std::string& name, channels carried, const track_interpolation& written) override;
    /// Throws std::logic_error for a row without its own angles.
    void row(const table_row& s) override;
    /// Throws keyrot::error unless every joint has a track, and the
    /// tracks the same frames.
    void finish() override;

private:
    std::unique_ptr<detail::chunked_output> sink_;
    std::shared_ptr<const bvh_source> source_;
    std::string frame_time_;  // as written
    write_options opts_;
    /// Per row: its time, the joint's Euler angles (degrees), its translation.
    track_store rows_{7};
};

}  // namespace keyrot
