// SPDX-License-Identifier: MIT
#include "io/gltf/gltf_read.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <limits>
#include <span>

#include "io/common/number_writer.hpp"
#include "io/gltf/gltf_accessor.hpp"
#include "keyrot/interpolate.hpp"
#include "keyrot/tolerances.hpp"

namespace keyrot {
namespace {

/// One sampler as its channels read it: key times, and per key the value
/// (and for CUBICSPLINE the in- and out-tangents), rotations in (w, x, y, z).
struct channel_curve {
    std::string path;  // "animations[0].samplers[2]", for messages
    std::vector<double> times;
    std::size_t width = 0;  // 4 for a rotation, 3 for a translation or scale, a weight per morph target
    method how = method::slerp;
    std::vector<double> values;  // per key: width values; CUBICSPLINE: in-tangent, value, out-tangent

    std::size_t keys() const { return times.size(); }
    /// The first key at or after `time` (as std::lower_bound), sought from
    /// the one found before: a track's key times are asked in increasing order.
    std::size_t first_key_from(double time) const {
        if (hint_ > 0 && !(times[hint_ - 1] < time)) hint_ = 0;  // (asked for an earlier time: from the start)
        std::size_t i = hint_;
        for (int steps = 0; i < times.size() && times[i] < time; ++i)
            if (++steps == 8) {  // far ahead: by bisection
                i = static_cast<std::size_t>(
                    std::lower_bound(times.begin() + static_cast<std::ptrdiff_t>(i), times.end(), time) - times.begin());
                break;
            }
        return hint_ = i;
    }
    /// The last key at or before `time`, which is within the keys.
    std::size_t key_before(double time) const {
        const std::size_t i = first_key_from(time);
        return i < times.size() && times[i] == time ? i : i - 1;
    }
    const double* element(std::size_t key, int part) const {  // part: -1 in-tangent, 0 value, 1 out-tangent
        const std::size_t per_key = how == method::cubicspline ? 3 : 1;
        const std::size_t slot = how == method::cubicspline ? static_cast<std::size_t>(part + 1) : 0;
        return values.data() + (key * per_key + slot) * width;
    }
    std::span<const double> get(std::size_t key, int part) const { return {element(key, part), width}; }

    mutable std::size_t hint_ = 0;  // first_key_from's last answer
};

/// What a channel of a node animates: its glTF target path.
enum class channel_kind { rotation, translation, scale, weights };

method method_of(const std::string& interpolation) {
    if (interpolation == "STEP") return method::step;
    if (interpolation == "CUBICSPLINE") return method::cubicspline;
    return method::slerp;
}

/// A sampler's times, stored as 32-bit floats (here widened), as the times
/// they stand for: k/fps where every one is the float nearest k/fps for one
/// rate (the rate of its first step, or a common one), so that frames made
/// at a rate read back at their times to the bit; else each the shortest
/// decimal that reads back as its float, as a text table of them would.
void read_as_written(std::vector<double>& times) {
    if (times.empty()) return;
    // Each time to k/fps in one pass, while every one is the float nearest k/fps; a time that is not
    // puts those before back (their floats are theirs) for the next rate.
    const auto on_rate = [&](double fps) {
        if (!(fps > 0 && std::isfinite(fps))) return false;
        constexpr double round_by = 0x1.8p52;  // (x + it) - it is x to the nearest integer, for |x| < 2^51
        for (std::size_t i = 0; i < times.size(); ++i) {
            const double frames = times[i] * fps, k = (frames + round_by) - round_by, at = k / fps;
            if (std::fabs(frames) >= 0x1p51 || static_cast<float>(at) != static_cast<float>(times[i])) {
                for (std::size_t j = 0; j < i; ++j) times[j] = static_cast<float>(times[j]);
                return false;
            }
            times[i] = at;
        }
        return true;
    };
    const double step = times.size() > 1 ? std::round(1 / (times[1] - times[0])) : 0;
    for (const double fps : {step, 1000 * step / 1001, 24.0, 25.0, 30.0, 48.0, 50.0, 60.0, 120.0})
        if (on_rate(fps)) return;
    for (double& t : times) t = shortest_decimal(static_cast<float>(t));
}

/// A sampler's input and output for a channel of `kind` (`width`: the
/// number of morph targets, for weights), into `c` (its memory reused).
void read_sampler(gltf_file& file, const gltf_json& sampler, const std::string& path, channel_kind kind,
                  std::size_t width, channel_curve& c) {
    const bool rotation = kind == channel_kind::rotation, weights = kind == channel_kind::weights;
    c.path = path, c.width = rotation ? 4 : weights ? width : 3, c.how = method::slerp, c.hint_ = 0;
    const std::string at = where(file.source, path);
    if (!sampler.is_object() || !sampler.contains("input") || !sampler.contains("output"))
        throw input_error(at, "expected an object with input and output");
    const std::string interpolation = string_member(sampler, "interpolation", "LINEAR", at);
    if (interpolation != "LINEAR" && interpolation != "STEP" && interpolation != "CUBICSPLINE")
        throw input_error(
            at, fmt::format("interpolation '{}': expected LINEAR, STEP or CUBICSPLINE", excerpt(interpolation)));
    c.how = method_of(interpolation);
    // Counts are checked before the accessors are read: zeros the file does
    // not store (an accessor with no bufferView) must not fill the memory.
    const accessor_size times = size_of_accessor(file, sampler["input"], path + ".input");
    if (times.count > times.stored + 1)
        throw input_error(at + ".input", fmt::format("{} key times, {} of them stored (the rest are 0): expected "
                                                     "strictly increasing times",
                                                     times.count, times.stored));
    read_accessor(file, sampler["input"], path + ".input", {"SCALAR", false}, c.times);
    for (std::size_t i = 1; i < c.times.size(); ++i)
        if (!(c.times[i] > c.times[i - 1]))
            throw input_error(at + ".input", fmt::format("time {} s at key {} is not after the previous key's {} s: "
                                                         "expected strictly increasing times",
                                                         c.times[i], i, c.times[i - 1]));
    read_as_written(c.times);
    const std::size_t per_key = c.how == method::cubicspline ? 3 : 1;
    const char* const spline_note = per_key == 3 ? " (CUBICSPLINE: in-tangent, value, out-tangent per key)" : "";
    const std::size_t elements = size_of_accessor(file, sampler["output"], path + ".output").count;
    if (weights && elements != c.keys() * per_key * c.width)
        throw input_error(at + ".output", fmt::format("{} weights for {} key times of {} morph targets: expected {}{}",
                                                      elements, c.keys(), c.width, c.keys() * per_key * c.width,
                                                      spline_note));
    if (!weights && elements != c.keys() * per_key)
        throw input_error(at + ".output", fmt::format("{} elements for {} key times: expected {}{}", elements,
                                                      c.keys(), c.keys() * per_key, spline_note));
    read_accessor(file, sampler["output"], path + ".output", {rotation ? "VEC4" : weights ? "SCALAR" : "VEC3", true},
                  c.values);
    if (c.how == method::cubicspline && c.keys() < 2)
        throw input_error(at, "CUBICSPLINE with one key: expected at least two");
    if (rotation)  // glTF stores x, y, z, w; keyrot's order is w, x, y, z
        for (std::size_t i = 0; i < c.values.size(); i += 4) {
            const double w = c.values[i + 3];
            c.values[i + 3] = c.values[i + 2], c.values[i + 2] = c.values[i + 1], c.values[i + 1] = c.values[i];
            c.values[i] = w;
        }
}

/// `from` into the start of `to`: a few numbers, copied in place rather
/// than by a call to memmove.
void put(std::span<const double> from, std::span<double> to) {
    for (std::size_t j = 0; j < from.size(); ++j) to[j] = from[j];
}

/// The curve's components at `time` within its keys, and, for
/// CUBICSPLINE, their derivative per second there (zero otherwise), as the
/// specification interpolates them: LINEAR component-wise (a rotation's
/// by slerp_at instead). Outside its keys a channel holds its
/// first or last value (as glTF clamps).
void evaluate(const channel_curve& c, double time, std::span<double> value, std::span<double> slope) {
    std::fill(slope.begin(), slope.end(), 0.0);
    if (time <= c.times.front()) return put(c.get(0, 0), value);
    if (time >= c.times.back()) return put(c.get(c.keys() - 1, 0), value);
    const std::size_t i = c.key_before(time);
    if (c.times[i] == time || c.how == method::step) return put(c.get(i, 0), value);
    const double seconds = c.times[i + 1] - c.times[i], h = (time - c.times[i]) / seconds;
    const auto v0 = c.get(i, 0), v1 = c.get(i + 1, 0);
    if (c.how == method::cubicspline) {
        const auto b0 = c.get(i, 1), a1 = c.get(i + 1, -1);
        hermite(v0, b0, v1, a1, seconds, h, value);
        // The derivative of hermite() by s, over the interval: per second.
        const double h2 = h * h;
        for (std::size_t j = 0; j < c.width; ++j)
            slope[j] = ((6 * h2 - 6 * h) * v0[j] + (6 * h - 6 * h2) * v1[j]) / seconds + (3 * h2 - 4 * h + 1) * b0[j] +
                       (3 * h2 - 2 * h) * a1[j];
        return;
    }
    for (std::size_t j = 0; j < c.width; ++j) value[j] = (1 - h) * v0[j] + h * v1[j];
}

/// A LINEAR rotation curve's value at `time` between two of its keys, as
/// the specification interpolates it: by slerp the short way.
quat slerp_at(const channel_curve& c, double time) {
    const std::size_t i = c.key_before(time);
    const double h = (time - c.times[i]) / (c.times[i + 1] - c.times[i]);
    const auto a = c.get(i, 0), b = c.get(i + 1, 0);
    const quat qa = normalized({a[0], a[1], a[2], a[3]});
    quat qb = normalized({b[0], b[1], b[2], b[3]});
    if (dot(qa, qb) < 0) qb = -qb;
    return slerp(qa, qb, h);
}

/// The node's own rotation, which a node animated only in translation keeps.
quat rest_rotation(const gltf_file& file, std::size_t node) {
    const gltf_json& n = top_array(file, "nodes")[node];
    if (!n.is_object() || !n.contains("rotation")) return {};
    const gltf_json& r = n["rotation"];
    const std::string at = where(file.source, fmt::format("nodes[{}].rotation", node));
    if (!r.is_array() || r.size() != 4 ||
        !std::all_of(r.begin(), r.end(), [](const gltf_json& v) { return v.is_number(); }))
        throw input_error(at, "expected four numbers (x, y, z, w)");
    const quat q{r[3].get<double>(), r[0].get<double>(), r[1].get<double>(), r[2].get<double>()};
    if (!(norm(q) > 0)) throw input_error(at, "quaternion is zero: expected a rotation");
    return q;
}

gltf_file load(std::istream& in, format f, const read_options& ro) {
    const std::filesystem::path directory = std::filesystem::path(ro.source).parent_path();
    return load_gltf(in, f, ro.source, directory.empty() ? "." : directory.string(), ro.max_bytes);
}

/// A glTF file's keys, track after track: each node's samplers are read
/// when its track's turn comes, so that one track's keys are held at a time.
class gltf_keys final : public key_reader {
public:
    /// The keys of `tracks`, tracks of the file.
    gltf_keys(std::shared_ptr<gltf_source> loaded, const read_options& ro, std::vector<node_track> tracks)
        : loaded_(std::move(loaded)), file_(loaded_->file), tracks_(std::move(tracks)), flags_(ro.settings) {}

    bool next(std::string& track, raw_key& k) override {
        while (key_ == times_.size()) {
            if (next_track_ == tracks_.size()) return false;
            begin(next_track_++);
        }
        // (compared rather than copied: most keys are of the track before, and
        // a compare costs less than a copy)
        if (const std::string& name = tracks_[next_track_ - 1].name; track != name) track = name;
        key_at(key_++, k);
        return true;
    }
    bool named() const override { return true; }
    location start() const override { return {}; }
    const key_settings& settings() const override { return settings_; }

private:
    /// Track i's channels read, and their times merged.
    void begin(std::size_t i) {
        const gltf_track_origin& o = tracks_[i].origin;
        const gltf_json& anim = top_array(file_, "animations")[o.animation];
        // (into the last track's channels: their memory is already mapped)
        const auto read = [&](std::optional<std::size_t> channel, channel_kind kind, std::optional<channel_curve>& c) {
            if (!channel) return c.reset();
            if (!c) c.emplace();
            const std::size_t s = anim["channels"][*channel]["sampler"];
            read_sampler(file_, anim["samplers"][s], fmt::format("animations[{}].samplers[{}]", o.animation, s), kind,
                         o.targets, *c);
        };
        read(o.rotation, channel_kind::rotation, rotation_);
        read(o.translation, channel_kind::translation, translation_);
        read(o.scale, channel_kind::scale, scale_);
        read(o.weights, channel_kind::weights, weights_);
        times_.clear();
        spline_ = false;
        for (const std::optional<channel_curve>* c : {&rotation_, &translation_, &scale_, &weights_}) {
            if (!*c) continue;
            // (each channel's times strictly increase: merged, not sorted)
            merged_.clear();
            std::set_union(times_.begin(), times_.end(), (*c)->times.begin(), (*c)->times.end(),
                           std::back_inserter(merged_));
            times_.swap(merged_);
            spline_ = spline_ || (*c)->how == method::cubicspline;
        }
        rest_ = rotation_ ? quat{} : rest_rotation(file_, o.node);
        node_ = o.node;
        settings_ = flags_;
        const auto how = [](const std::optional<channel_curve>& c, method absent) { return c ? c->how : absent; };
        settings_.interpolation = track_interpolation{how(rotation_, method::step), how(translation_, method::slerp),
                                                      how(scale_, method::slerp), how(weights_, method::slerp), 0x1p-24};
        key_ = 0;
    }

    /// Key j of the current track into `raw` (raw_key::reset): each
    /// channel's key there, or its curve's value.
    void key_at(std::size_t j, raw_key& raw) const {
        const double t = times_[j];
        raw.reset();
        raw.time = t;
        // Tangents only in a track with a CUBICSPLINE channel: a spline key
        // zeroed for every other key would cost more than the rest here.
        full_spline_key* const s = spline_ ? &raw.spline.emplace() : nullptr;
        if (rotation_) {
            std::array<double, 4> v{}, in{}, out{};
            const std::size_t i = components_at(*rotation_, t, true, v, tangents(std::span(in)), tangents(std::span(out)));
            const bool key = i != between_keys;
            quat q{v[0], v[1], v[2], v[3]};
            if (!key && rotation_->how == method::slerp && t > rotation_->times.front() && t < rotation_->times.back())
                q = slerp_at(*rotation_, t);
            if (s) {
                s->rotation = q;
                s->rotation_in = {in[0], in[1], in[2], in[3]}, s->rotation_out = {out[0], out[1], out[2], out[3]};
            }
            // A value the curve passes between keys is not unit (a spline's, at least): it counts as given normalised.
            if (const double n = key ? 0 : norm(q); n > 0) q = normalized(q, n);
            // (the other twelve values reset zeroed)
            raw.values[0] = q.w, raw.values[1] = q.x, raw.values[2] = q.y, raw.values[3] = q.z;
            // Where make_key may say something of the key (zero, or renormalised): formatted only then.
            // (|q|² is off 1 by more than |q| is: the square root only for a key that may be.)
            if (std::fabs(dot(q, q) - 1) > tol::unit_norm && std::fabs(norm(q) - 1) > tol::unit_norm) {
                const channel_curve& other = translation_ ? *translation_ : scale_ ? *scale_ : *weights_;
                raw.at.path = key ? fmt::format("{}.output[{}]", rotation_->path, i)
                                  : fmt::format("{}.input", other.path);
            }
        } else {
            if (std::fabs(norm(rest_) - 1) > tol::unit_norm) raw.at.path = fmt::format("nodes[{}].rotation", node_);
            raw.values[0] = rest_.w, raw.values[1] = rest_.x, raw.values[2] = rest_.y, raw.values[3] = rest_.z;
            if (s) s->rotation = rest_;
        }
        vec3 none;  // (where the tangents go that a key without a spline does not carry)
        if (translation_)
            raw.translation = vector_at(*translation_, t, s ? s->translation_in : none, s ? s->translation_out : none);
        if (scale_) raw.scale = vector_at(*scale_, t, s ? s->scale_in : none, s ? s->scale_out : none);
        if (weights_) {
            // Held outside its keys, as glTF clamps: every key of the track has weights.
            const std::size_t n = weights_->width;
            raw.weights.resize(n);
            if (s) s->weights_in.resize(n), s->weights_out.resize(n);
            components_at(*weights_, t, true, raw.weights, s ? std::span(s->weights_in) : std::span<double>(),
                          s ? std::span(s->weights_out) : std::span<double>());
        }
    }

    /// Room for a channel's tangents, where the track has a CUBICSPLINE
    /// channel; none otherwise (no channel has any, and none is asked for).
    std::span<double> tangents(std::span<double> room) const { return spline_ ? room : room.first(0); }

    /// Channel `c` at time `t` (one of the track's key times): its key's
    /// value there and, for CUBICSPLINE, the key's tangents; or the curve's
    /// value and slope (LINEAR component-wise). With `held`, the channel
    /// holds its first and last values beyond its keys, so the tangents
    /// there are zero. Returns the key's index where `t` is one of c's
    /// keys, else between_keys. (Not an optional: GCC returns that through
    /// memory in pieces, and reading it back stalls.)
    std::size_t components_at(const channel_curve& c, double t, bool held, std::span<double> value,
                              std::span<double> in, std::span<double> out) const {
        const auto key = c.times.begin() + static_cast<std::ptrdiff_t>(c.first_key_from(t));
        if (key == c.times.end() || *key != t) {
            evaluate(c, t, value, in);
            put(in, out);
            return between_keys;
        }
        const std::size_t i = static_cast<std::size_t>(key - c.times.begin());
        put(c.get(i, 0), value);
        std::fill(in.begin(), in.end(), 0.0), std::fill(out.begin(), out.end(), 0.0);
        if (c.how == method::cubicspline) {
            // The first key's in-tangent and the last's out-tangent do nothing in glTF; zero, they
            // keep the channel held where the other channels' keys reach beyond it.
            if (!(held && i == 0 && times_.front() < t)) put(c.get(i, -1), in);
            if (!(held && i + 1 == c.keys() && times_.back() > t)) put(c.get(i, 1), out);
        }
        return i;
    }

    /// A translation or scale channel at time `t`, with its tangents there:
    /// its key, or its curve's value; nothing outside its keys (it is
    /// held), but a channel of one key is that key at every time: a value
    /// for the whole animation, as glTF holds it (and as keyrot writes a
    /// channel that never changes).
    std::optional<vec3> vector_at(const channel_curve& c, double t, vec3& in, vec3& out) const {
        if (c.keys() == 1) {
            const auto v = c.get(0, 0);
            return vec3{v[0], v[1], v[2]};
        }
        if (t < c.times.front() || t > c.times.back()) return std::nullopt;
        std::array<double, 3> v{}, before{}, after{};
        components_at(c, t, false, v, tangents(std::span(before)), tangents(std::span(after)));
        in = {before[0], before[1], before[2]}, out = {after[0], after[1], after[2]};
        return vec3{v[0], v[1], v[2]};
    }

    static constexpr std::size_t between_keys = std::numeric_limits<std::size_t>::max();

    std::shared_ptr<gltf_source> loaded_;
    gltf_file& file_;  // loaded_'s
    std::vector<node_track> tracks_;
    key_settings flags_, settings_;
    std::size_t next_track_ = 0, key_ = 0, node_ = 0;
    std::optional<channel_curve> rotation_, translation_, scale_, weights_;
    std::vector<double> times_, merged_;
    bool spline_ = false;
    quat rest_;
};

}  // namespace

std::unique_ptr<key_reader> make_gltf_reader(std::istream& in, format f, const read_options& ro, warnings& warn) {
    return make_gltf_reader(std::make_shared<gltf_source>(gltf_source{load(in, f, ro), {}}), ro, warn);
}

std::unique_ptr<key_reader> make_gltf_reader(std::shared_ptr<gltf_source> loaded, const read_options& ro,
                                             warnings& warn) {
    std::vector<node_track> tracks = tracks_of(loaded->file, ro, warn);  // (what it warns of, said again)
    return std::make_unique<gltf_keys>(std::move(loaded), ro, std::move(tracks));
}

std::size_t read_buffers(gltf_source& loaded) {
    std::size_t bytes = 0;
    for (std::size_t i = 0; i < top_array(loaded.file, "buffers").size(); ++i)
        bytes += buffer_bytes(loaded.file, i).size();
    return bytes;
}

std::vector<std::unique_ptr<key_reader>> make_gltf_track_readers(const std::shared_ptr<gltf_source>& loaded,
                                                                  const read_options& ro) {
    read_buffers(*loaded);  // (a reader reads a buffer on first use, which two at once must not)
    std::vector<std::unique_ptr<key_reader>> readers;
    for (std::size_t i = 0; i < loaded->tracks.size(); ++i)
        readers.push_back(std::make_unique<gltf_keys>(loaded, ro, std::vector{loaded->tracks[i]}));
    return readers;
}

std::shared_ptr<gltf_source> read_gltf_source(std::istream& in, format f, const read_options& ro, warnings& warn) {
    auto source = std::make_shared<gltf_source>();
    source->file = load(in, f, ro);
    source->tracks = tracks_of(source->file, ro, warn);
    return source;
}

}  // namespace keyrot
