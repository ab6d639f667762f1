#include "io/bvh/bvh_write.hpp"

#include <fmt/format.h>

#include "io/common/chunked_output.hpp"
#include "io/common/layout.hpp"

namespace keyrot {

bvh_output::bvh_output(const std::optional<std::string>& target, std::ostream& out,
                       std::shared_ptr<const bvh_source> source, std::size_t frames, double frame_time,
                       const write_options& opts)
    : sink_(std::make_unique<detail::chunked_output>(target, out, opts.commit)),
      source_(std::move(source)),
      frames_(frames),
      opts_(opts),
      waiting_(source_->joints.size()),
      previous_(source_->joints.size()) {
    std::string& text = sink_->text();
    const std::string& nl = source_->newline;
    text += source_->hierarchy;
    text += "MOTION" + nl + fmt::format("Frames: {}", frames) + nl + "Frame Time: ";
    append_number(text, frame_time, std::nullopt);
    text += nl;
}

bvh_output::~bvh_output() = default;

void bvh_output::row(std::size_t joint, const sample& s) {
    auto& rows = waiting_[joint];
    if (rows.empty()) ++complete_;
    rows.push_back({s.time, s.rotation, s.translation.value_or(vec3{})});
    if (complete_ == waiting_.size()) write_frame();
}

void bvh_output::write_frame() {
    if (written_ == frames_) throw error(fmt::format("BVH output: more frames than the {} stated", frames_));
    std::string& text = sink_->text();
    const double time = waiting_.front().front().time;
    bool first = true;
    for (std::size_t j = 0; j < waiting_.size(); ++j) {
        const bvh_joint& joint = source_->joints[j];
        const frame_row& r = waiting_[j].front();
        if (r.time != time)
            throw error(
                fmt::format("joint '{}' has a frame at {} s where '{}' has one at {} s: expected the same "
                            "frames for every joint, as BVH stores them",
                            joint.name, r.time, source_->joints.front().name, time));
        previous_[j] = written_ == 0 ? to_euler(r.rotation, joint.euler).angles
                                     : continuous_euler(r.rotation, joint.euler, previous_[j]);
        for (const int kind : joint.kinds) {
            if (!first) text += ' ';
            first = false;
            double v = 0;
            if (kind < 3) {
                v = kind == 0 ? r.translation.x : kind == 1 ? r.translation.y : r.translation.z;
            } else {
                for (std::size_t a = 0; a < 3; ++a)
                    if (joint.euler.axes[a] == kind - 3) v = from_radians(previous_[j][a], angle_unit::degrees);
            }
            append_number(text, v, opts_.precision);
        }
        waiting_[j].pop_front();
        if (waiting_[j].empty()) --complete_;
    }
    text += source_->newline;
    ++written_;
    sink_->maybe_flush();
}

void bvh_output::finish() {
    const auto longest = std::max_element(waiting_.begin(), waiting_.end(),
                                          [](const auto& a, const auto& b) { return a.size() < b.size(); });
    if (written_ != frames_ || !longest->empty())
        throw error(fmt::format("BVH output: {} frames made, and {} more of some joints: expected {}", written_,
                                longest->size(), frames_));
    sink_->finish();
}

}  // namespace keyrot
