#include "io/bvh_write.hpp"

#include <fmt/format.h>

#include "io/output.hpp"

namespace keyrot {
namespace {

class bvh_table final : public table_output {
public:
    bvh_table(const std::optional<std::string>& target, std::ostream& out, std::shared_ptr<bvh_source> source,
              const table_info& info, const write_options& opts, warnings& warn)
        : target_(target), out_(out), source_(std::move(source)), info_(info), opts_(opts), warn_(warn) {}

    void begin_track(const std::string& name, channels, const track_interpolation&) override {
        tracks_.push_back({name, {}});
        // Every joint has the first one's frames: no copying as they come.
        if (tracks_.size() > 1) tracks_.back().rows.reserve(tracks_.front().rows.size());
    }
    void row(const sample& s) override {
        tracks_.back().rows.push_back({s.time, s.rotation, s.translation.value_or(vec3{})});
    }
    void finish() override {
        const bvh_source& src = *source_;
        if (tracks_.size() != src.joints.size())
            throw input_error(warn_.source(), fmt::format("{} tracks for the {} joints with channels: expected one "
                                                          "track per joint",
                                                          tracks_.size(), src.joints.size()));
        const std::size_t frames = tracks_.front().rows.size();
        for (const track_rows& t : tracks_)
            if (t.rows.size() != frames || t.rows.front().time != tracks_.front().rows.front().time)
                throw input_error(warn_.source(),
                                  fmt::format("track '{}' has {} rows from {} s, track '{}' {} from {} s: expected "
                                              "the same frames for every joint, as BVH stores them",
                                              tracks_.front().name, frames, tracks_.front().rows.front().time, t.name,
                                              t.rows.size(), t.rows.front().time));
        std::string text = src.hierarchy;
        const std::string& nl = src.newline;
        text += "MOTION" + nl + fmt::format("Frames: {}", frames) + nl + "Frame Time: ";
        append_number(text, info_.fps ? 1 / *info_.fps : src.frame_time, std::nullopt);
        text += nl;
        std::vector<std::array<double, 3>> previous(tracks_.size());
        for (std::size_t f = 0; f < frames; ++f) {
            bool first = true;
            for (std::size_t j = 0; j < tracks_.size(); ++j) {
                const bvh_joint& joint = src.joints[j];
                const frame_row& r = tracks_[j].rows[f];
                previous[j] = f == 0 ? to_euler(r.rotation, joint.euler).angles
                                     : continuous_euler(r.rotation, joint.euler, previous[j]);
                const vec3& p = r.translation;
                for (const int kind : joint.kinds) {
                    if (!first) text += ' ';
                    first = false;
                    double v = 0;
                    if (kind < 3) {
                        v = kind == 0 ? p.x : kind == 1 ? p.y : p.z;
                    } else {
                        for (std::size_t a = 0; a < 3; ++a)
                            if (joint.euler.axes[a] == kind - 3) v = from_radians(previous[j][a], angle_unit::degrees);
                    }
                    append_number(text, v, opts_.precision);
                }
            }
            text += nl;
        }
        if (target_)
            write_file_atomically(*target_, text);
        else
            write_to_stream(out_, text);
    }

private:
    /// What BVH keeps of a row.
    struct frame_row {
        double time;
        quat rotation;
        vec3 translation;  // zero where the row has none
    };
    struct track_rows {
        std::string name;
        std::vector<frame_row> rows;
    };
    std::optional<std::string> target_;
    std::ostream& out_;
    std::shared_ptr<bvh_source> source_;
    table_info info_;
    write_options opts_;
    warnings& warn_;
    std::vector<track_rows> tracks_;
};

}  // namespace

std::unique_ptr<table_output> make_bvh_table(const std::optional<std::string>& target, std::ostream& out,
                                             std::shared_ptr<bvh_source> source, const table_info& info,
                                             const write_options& opts, warnings& warn) {
    return std::make_unique<bvh_table>(target, out, std::move(source), info, opts, warn);
}

}  // namespace keyrot
