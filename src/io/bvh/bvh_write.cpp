#include "io/bvh/bvh_write.hpp"

#include <fmt/format.h>

#include "io/common/chunked_output.hpp"
#include "io/common/layout.hpp"

namespace keyrot {

bvh_output::bvh_output(const std::optional<std::string>& target, std::ostream& out,
                       std::shared_ptr<const bvh_source> source, double frame_time, const write_options& opts)
    : sink_(std::make_unique<detail::chunked_output>(target, out, opts.commit)),
      source_(std::move(source)),
      frame_time_(frame_time),
      opts_(opts) {}

bvh_output::~bvh_output() = default;

void bvh_output::begin_track(const std::string& name, channels, const track_interpolation&) {
    if (rows_.tracks() == source_->joints.size())
        throw error(fmt::format("BVH output: a track '{}' after the hierarchy's {} joints: expected one track per joint",
                                name, source_->joints.size()));
    rows_.begin_track();
}

void bvh_output::row(const table_row& s) {
    const euler_seq& seq = source_->joints[rows_.tracks() - 1].euler;
    const bool first = rows_.rows(rows_.tracks() - 1) == 0;
    previous_ = first ? to_euler(s.rotation, seq).angles : continuous_euler(s.rotation, seq, previous_);
    const vec3 t = s.translation.value_or(vec3{});
    const double values[7] = {s.time, previous_[0], previous_[1], previous_[2], t.x, t.y, t.z};
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
    append_number(text, frame_time_, std::nullopt);
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
                        if (joint.euler.axes[a] == kind - 3) v = from_radians(r[1 + a], angle_unit::degrees);
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
