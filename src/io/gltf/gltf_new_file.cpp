// SPDX-License-Identifier: MIT
// A new glTF file (of CSV, JSON or BVH) written as its rows come, in
// memory that does not grow with the take (make_new_gltf_file).
#include "io/gltf/gltf_write.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <map>
#include <optional>
#include <tuple>

#include "io/gltf/gltf_buffer.hpp"
#include "io/json/json.hpp"

namespace keyrot {
namespace {

using namespace detail;

/// A channel of `animation.channels`: sampler `sampler` animates `path` of node `node`.
gltf_json channel_json(std::size_t sampler, std::size_t node, const char* path) {
    gltf_json c = gltf_json::object();
    c["sampler"] = sampler;
    c["target"] = gltf_json::object();
    c["target"]["node"] = node;
    c["target"]["path"] = path;
    return c;
}

/// A new file (a node per track, or the nodes of a skeleton, and one
/// animation) written as the rows come: each channel's 32-bit floats (with
/// `short_rotations`, the rotation's normalised 16-bit integers) are set
/// aside in a temporary file, and a track's are appended to the buffer
/// when it ends, so that memory does not grow with the take. A row is
/// LINEAR or STEP, never CUBICSPLINE (only a glTF input has splines).
class new_file_table final : public table_output {
public:
    new_file_table(format f, const std::optional<std::string>& target, std::ostream& out, commit_mode commit,
                   bool short_rotations, std::vector<gltf_node> skeleton, warnings& warn)
        : f_(f), target_(target), commit_(commit), out_(out), skeleton_(std::move(skeleton)),
          b_(json_, warn.source()) {
        if (short_rotations) rotation_.stored = component::normalized_short;
    }
    void begin_track(const std::string& name, channels carried, const track_interpolation& written) override {
        end_track();
        if (carried.weights)
            throw input_error(b_.source, fmt::format("track '{}' has morph weights, which a new glTF file cannot hold "
                                                     "without the mesh they weigh: expected a glTF input, whose file "
                                                     "is rewritten, or another output format",
                                                     name));
        tracks_.push_back({name, written, {}});
        for (spooled_channel* c : {&rotation_, &translation_, &scale_}) c->clear();
    }
    void row(const table_row& s) override {
        // (the track's name in a message only when there is one to give)
        const auto where = [&] {
            const std::string& name = tracks_.back().name;
            return name.empty() ? b_.source : keyrot::where(b_.source, fmt::format("track '{}'", name));
        };
        const float time = time_after(s.time, rotation_.count ? &rotation_.last : nullptr, previous_time_, where);
        previous_time_ = s.time;
        rotation_.add(time, {s.rotation.x, s.rotation.y, s.rotation.z, s.rotation.w}, where, "rotation");
        if (s.translation)
            translation_.add(time, {s.translation->x, s.translation->y, s.translation->z}, where, "translation");
        if (s.scale) scale_.add(time, {s.scale->x, s.scale->y, s.scale->z}, where, "scale");
    }
    void finish() override {
        end_track();
        std::vector<gltf_node> skeleton = skeleton_;
        if (skeleton.empty())
            for (std::size_t i = 0; i < tracks_.size(); ++i)
                skeleton.push_back({tracks_[i].name.empty() ? "track" : tracks_[i].name, std::nullopt, {}, i});
        if (std::count_if(skeleton.begin(), skeleton.end(), [](const gltf_node& n) { return n.track.has_value(); }) !=
            static_cast<std::ptrdiff_t>(tracks_.size()))
            throw input_error(b_.source, fmt::format("{} tracks for a skeleton of {} nodes: expected a track per "
                                                     "animated joint",
                                                     tracks_.size(), skeleton.size()));
        gltf_json json = gltf_json::object();
        json["asset"] = {{"version", "2.0"}, {"generator", "keyrot"}};
        json["scene"] = 0;
        json["scenes"] = gltf_json::array({{{"nodes", gltf_json::array()}}});
        json["nodes"] = gltf_json::array();
        gltf_json channels = gltf_json::array();
        for (std::size_t k = 0; k < skeleton.size(); ++k) {
            const gltf_node& n = skeleton[k];
            json_quote(n.name);  // throws for a name that is not UTF-8, which JSON cannot hold
            gltf_json node = {{"name", n.name}};
            const vec3& t = n.translation;
            if (t.x != 0 || t.y != 0 || t.z != 0)
                for (const double x : {t.x, t.y, t.z}) node["translation"].push_back(single(x, b_.source, "offset"));
            json["nodes"].push_back(std::move(node));
            if (n.parent) json["nodes"][*n.parent]["children"].push_back(k);
            else json["scenes"][0]["nodes"].push_back(k);
            if (!n.track) continue;
            for (const auto& [path, sampler] : tracks_[*n.track].samplers)
                channels.push_back(channel_json(sampler, k, path));
        }
        for (const char* name : {"bufferViews", "accessors"})
            if (json_.contains(name)) json[name] = std::move(json_[name]);
        json["animations"] = gltf_json::array({{{"channels", std::move(channels)}, {"samplers", std::move(samplers_)}}});
        json["buffers"] = gltf_json::array({gltf_json::object()});
        put_file(json, b_.bin, f_, target_, commit_, out_);
    }

private:
    /// A channel of the current track: its key times as 32-bit floats and
    /// its values as `stored`, set aside; its first value, and whether
    /// every one is that.
    struct spooled_channel {
        byte_spool times, values;
        component stored = component::float32;
        std::size_t count = 0;
        float first = 0, last = 0;
        std::string first_value;
        bool still = true;
        void clear() { times.clear(), values.clear(), count = 0, still = true; }
        void add(float time, std::initializer_list<double> value, const auto& where, const char* what) {
            std::string bytes;
            append_float(bytes, time);
            times.append(bytes);
            bytes.clear();
            if (stored == component::normalized_short)
                append_normalized_shorts(bytes, std::span<const double, 4>(value.begin(), 4));
            else
                for (const double v : value) append_float(bytes, single_at(v, where, what));
            values.append(bytes);
            if (count++ == 0) first = time, first_value = bytes;
            else still = still && bytes == first_value;
            last = time;
        }
    };
    struct written_track {
        std::string name;
        track_interpolation how;
        std::vector<std::pair<const char*, std::size_t>> samplers;  // (path, sampler)
    };

    /// The current track's channels into the buffer, as samplers (the
    /// rotation's times shared by a channel keyed on every row). A
    /// translation or scale on every row that never changes is written as
    /// one key, which glTF holds for the whole animation and keyrot reads at
    /// every key of the track.
    void end_track() {
        if (tracks_.empty() || !tracks_.back().samplers.empty() || rotation_.count == 0) return;
        written_track& t = tracks_.back();
        std::optional<std::size_t> rotation_times;
        for (const auto& [c, path, width, how] : {std::tuple(&rotation_, "rotation", 4, t.how.rotation),
                                                  std::tuple(&translation_, "translation", 3, t.how.translation),
                                                  std::tuple(&scale_, "scale", 3, t.how.scale)}) {
            if (c->count == 0) continue;
            const auto times = [&, c = c] { return time_accessor(*c); };
            const bool one_key = c != &rotation_ && c->count == rotation_.count && c->count > 1 && c->still;
            std::size_t input;
            if (one_key) input = single_time(c->first);
            else if (c->count != rotation_.count) input = times();
            else input = rotation_times ? *rotation_times : *(rotation_times = times());
            const std::size_t values = one_key ? b_.view(c->first_value) : b_.view(c->values);
            gltf_json sampler = gltf_json::object();
            sampler["input"] = input;
            sampler["interpolation"] = interpolation_name(how);
            sampler["output"] =
                b_.accessor(values, one_key ? 1 : c->count, static_cast<std::size_t>(width), {}, {}, c->stored);
            samplers_.push_back(std::move(sampler));
            t.samplers.emplace_back(path, samplers_.size() - 1);
        }
    }
    /// The accessor of channel c's key times: the one written last where
    /// they are its bytes (a rig's joints have the same frames), else a new one.
    std::size_t time_accessor(spooled_channel& c) {
        if (last_times_ && last_times_->count == c.count && last_times_->first == c.first &&
            last_times_->last == c.last && b_.bin.holds_at(last_times_->offset, c.times))
            return last_times_->accessor;
        const std::size_t view = b_.view(c.times);
        last_times_ = written_times{b_.accessor(view, c.count, 1, {c.first}, {c.last}),
                                    json_["bufferViews"][view]["byteOffset"].get<std::size_t>(), c.count, c.first,
                                    c.last};
        return last_times_->accessor;
    }
    /// The accessor of the one key time `time`, shared by the tracks whose first key it is.
    std::size_t single_time(float time) {
        const auto [at, made] = single_times_.try_emplace(std::bit_cast<std::uint32_t>(time), 0);
        if (made) {
            std::string bytes;
            append_float(bytes, time);
            at->second = b_.accessor(b_.view(bytes), 1, 1, {time}, {time});
        }
        return at->second;
    }

    format f_;
    std::optional<std::string> target_;
    commit_mode commit_;
    std::ostream& out_;
    std::vector<gltf_node> skeleton_;
    gltf_json json_ = gltf_json::object();  // the bufferViews and accessors, as they are made
    buffer_builder b_;
    gltf_json samplers_ = gltf_json::array();
    std::vector<written_track> tracks_;
    spooled_channel rotation_, translation_, scale_;
    std::map<std::uint32_t, std::size_t> single_times_;  // single_time's, by the time's bits
    struct written_times {
        std::size_t accessor, offset;  // the accessor, and where its bytes are in the buffer
        std::size_t count;
        float first, last;
    };
    std::optional<written_times> last_times_;  // time_accessor's last new one
    double previous_time_ = 0;
};

}  // namespace

std::unique_ptr<table_output> make_new_gltf_file(format f, const std::optional<std::string>& target, std::ostream& out,
                                                 commit_mode commit, bool short_rotations,
                                                 std::vector<gltf_node> skeleton, warnings& warn) {
    return std::make_unique<new_file_table>(f, target, out, commit, short_rotations, std::move(skeleton), warn);
}

}  // namespace keyrot
