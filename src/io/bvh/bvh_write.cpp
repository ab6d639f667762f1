// SPDX-License-Identifier: MIT
#include "io/bvh/bvh_write.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "io/common/chunked_output.hpp"
#include "io/common/layout.hpp"

namespace keyrot {

bvh_output::bvh_output(const std::optional<std::string>& target, std::ostream& out,
                       std::shared_ptr<const bvh_source> source, std::optional<double> fps, const write_options& opts)
    : sink_(std::make_unique<detail::chunked_output>(target, out, opts.commit)),
      source_(std::move(source)),
      frame_time_(source_->frame_time_text),
      opts_(opts) {
    if (fps && *fps != source_->fps) frame_time_.clear(), append_number(frame_time_, 1 / *fps, std::nullopt);
}

bvh_output::~bvh_output() = default;

void bvh_output::begin_track(const std::string& name, channels, const track_interpolation&) {
    if (rows_.tracks() == source_->joints.size())
        throw error(fmt::format("BVH output: a track '{}' after the hierarchy's {} joints: expected one track per joint",
                                name, source_->joints.size()));
    rows_.begin_track();
}

void bvh_output::row(const table_row& s) {
    if (!s.own) throw std::logic_error("BVH output: a row without its joint's angles");
    const auto& angles = s.own->values;
    const vec3 t = s.translation.value_or(vec3{});
    const double values[7] = {s.time, angles[0], angles[1], angles[2], t.x, t.y, t.z};
    rows_.push(values);
}

void bvh_output::finish() {
    const auto& joints = source_->joints;
    if (rows_.tracks() != joints.size())
        throw error(fmt::format("BVH output: tracks of {} joints: expected the hierarchy's {}", rows_.tracks(),
                                joints.size()));
    const std::size_t frames = rows_.rows(0);
    for (std::size_t j = 1; j < joints.size(); ++j)
        if (rows_.rows(j) != frames)
            throw error(fmt::format("joint '{}' has {} frames where '{}' has {}: expected the same frames for every "
                                    "joint, as BVH stores them",
                                    joints[j].name, rows_.rows(j), joints.front().name, frames));
    std::string& text = sink_->text();
    const std::string& nl = source_->newline;
    text += source_->hierarchy;
    text += "MOTION" + nl + fmt::format("Frames: {}", frames) + nl + "Frame Time: ";
    text += frame_time_;
    text += nl;
    for (std::size_t k = 0; k < frames; ++k) {
        const double time = rows_.at(0, k)[0];
        bool first = true;
        for (std::size_t j = 0; j < joints.size(); ++j) {
            const bvh_joint& joint = joints[j];
            const double* r = rows_.at(j, k);
            if (r[0] != time)
                throw error(fmt::format("joint '{}' has a frame at {} s where '{}' has one at {} s: expected the same "
                                        "frames for every joint, as BVH stores them",
                                        joint.name, r[0], joints.front().name, time));
            for (const int kind : joint.kinds) {
                if (!first) text += ' ';
                first = false;
                double v = 0;
                if (kind < 3) {
                    v = r[4 + kind];
                } else {
                    for (std::size_t a = 0; a < 3; ++a)
                        if (joint.euler.axes[a] == kind - 3) v = r[1 + a];
                }
                append_number(text, v, opts_.precision);
            }
        }
        text += nl;
        sink_->maybe_flush();
    }
    sink_->finish();
}

}  // namespace keyrot
