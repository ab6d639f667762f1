#include "io/gltf/gltf_read.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <span>

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

std::string node_name(const gltf_file& file, std::size_t node) {
    const gltf_json& n = top_array(file, "nodes")[node];
    if (n.is_object() && n.contains("name") && n["name"].is_string() && !n["name"].get<std::string>().empty())
        return n["name"];
    return fmt::format("node{}", node);
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

/// The animations to read: all, or the one `wanted` names.
std::vector<std::size_t> chosen_animations(const gltf_file& file, const std::optional<std::string>& wanted) {
    const gltf_json& animations = top_array(file, "animations");
    if (animations.empty()) throw input_error(file.source, "no animations: expected a glTF file with an animation");
    std::vector<std::string> names;
    for (std::size_t a = 0; a < animations.size(); ++a) {
        const gltf_json& anim = animations[a];
        names.push_back(anim.is_object() && anim.contains("name") && anim["name"].is_string() &&
                                !anim["name"].get<std::string>().empty()
                            ? anim["name"].get<std::string>()
                            : fmt::format("animation{}", a));
    }
    if (!wanted) {
        std::vector<std::size_t> all(animations.size());
        for (std::size_t a = 0; a < all.size(); ++a) all[a] = a;
        return all;
    }
    for (std::size_t a = 0; a < names.size(); ++a)
        if (names[a] == *wanted || std::to_string(a) == *wanted) return {a};
    throw input_error(
        file.source,
        fmt::format("--animation {}: no such animation: expected one of {} or an index 0 to {}", excerpt(*wanted),
                    excerpt(fmt::format("{}", fmt::join(names, ", ")), 200), names.size() - 1));
}

std::string animation_name(const gltf_file& file, std::size_t a) {
    const gltf_json& anim = top_array(file, "animations")[a];
    if (anim.contains("name") && anim["name"].is_string() && !anim["name"].get<std::string>().empty())
        return anim["name"];
    return fmt::format("animation{}", a);
}

/// A track to be: a node's channels in one animation, and its name.
struct node_track {
    gltf_track_origin origin;
    std::string name;
};

/// How many morph targets node `node`'s mesh has (its weights channel has a
/// weight for each); an input_error at `at` where it has none.
std::size_t morph_targets(const gltf_file& file, std::size_t node, const std::string& at) {
    const gltf_json& n = top_array(file, "nodes")[node];
    const std::string here = where(file.source, fmt::format("nodes[{}]", node));
    if (!n.is_object() || !n.contains("mesh"))
        throw input_error(at, fmt::format("a weights channel of node {}, which has no mesh: expected a node whose mesh "
                                          "has morph targets",
                                          node));
    const gltf_json& mesh = top_array(file, "meshes")[index_into(file, n["mesh"], "meshes", here + ".mesh")];
    std::size_t targets = 0;
    if (mesh.is_object() && mesh.contains("primitives") && mesh["primitives"].is_array() &&
        !mesh["primitives"].empty() && mesh["primitives"][0].is_object() && mesh["primitives"][0].contains("targets") &&
        mesh["primitives"][0]["targets"].is_array())
        targets = mesh["primitives"][0]["targets"].size();
    if (targets == 0)
        throw input_error(at, fmt::format("a weights channel of node {}, whose mesh has no morph targets: expected "
                                          "a mesh with targets",
                                          node));
    return targets;
}

/// Animation `a`'s rotation, translation, scale and weights channels, by
/// node in the order of their first channel. Other channels are noted and
/// left out.
std::vector<node_track> channels_of(const gltf_file& file, std::size_t a, warnings& warn) {
    const gltf_json& anim = top_array(file, "animations")[a];
    const std::string path = fmt::format("animations[{}]", a);
    const std::string at = where(file.source, path);
    if (!anim.is_object() || !anim.contains("channels") || !anim["channels"].is_array() || !anim.contains("samplers") ||
        !anim["samplers"].is_array())
        throw input_error(at, "expected an object with channels and samplers");
    const gltf_json &channels = anim["channels"], &samplers = anim["samplers"];
    std::vector<node_track> nodes;
    std::map<std::size_t, std::size_t> index;  // node -> its entry
    for (std::size_t c = 0; c < channels.size(); ++c) {
        const gltf_json& ch = channels[c];
        const std::string here = fmt::format("{}.channels[{}]", at, c);
        if (!ch.is_object() || !ch.contains("target") || !ch["target"].is_object() || !ch.contains("sampler"))
            throw input_error(here, "expected an object with a sampler and a target");
        const gltf_json& target = ch["target"];
        const std::string what = string_member(target, "path", "", here + ".target");
        if (!target.contains("node")) {
            warn.once("gltf-no-node",
                      fmt::format("{}.channels[{}]: a channel without a node (an extension's) is left out", path, c));
            continue;
        }
        const std::size_t node = index_into(file, target["node"], "nodes", here + ".target.node");
        if (what != "rotation" && what != "translation" && what != "scale" && what != "weights") {
            warn.once("gltf-" + what, fmt::format("{} channels are not read: keyrot reads rotation, translation, "
                                                  "scale and weights channels (first at {}.channels[{}])",
                                                  excerpt(what.empty() ? "unnamed" : what), path, c));
            continue;
        }
        if (!ch["sampler"].is_number_unsigned() || ch["sampler"].get<std::size_t>() >= samplers.size())
            throw input_error(here + ".sampler", fmt::format("{}: expected an index into {}.samplers",
                                                             excerpt(ch["sampler"].dump()), path));
        const auto [it, added] = index.emplace(node, nodes.size());
        if (added) nodes.push_back({{a, node, std::nullopt, std::nullopt, std::nullopt, std::nullopt, 0}, {}});
        gltf_track_origin& o = nodes[it->second].origin;
        auto& slot = what == "rotation"      ? o.rotation
                     : what == "translation" ? o.translation
                     : what == "scale"       ? o.scale
                                             : o.weights;
        if (what == "weights") o.targets = morph_targets(file, node, here + ".target.node");
        if (slot)
            throw input_error(
                here, fmt::format("node {}'s {} is animated twice in one animation: expected once", node, what));
        slot = c;
    }
    return nodes;
}

/// Every track of the file (or of the one animation ro.animation names), named.
std::vector<node_track> tracks_of(const gltf_file& file, const read_options& ro, warnings& warn) {
    const std::vector<std::size_t> animations = chosen_animations(file, ro.animation);
    std::vector<node_track> tracks;
    std::set<std::string> names;
    for (const std::size_t a : animations) {
        for (node_track& n : channels_of(file, a, warn)) {
            n.name = node_name(file, n.origin.node);
            if (animations.size() > 1) n.name = animation_name(file, a) + "/" + n.name;
            check_track_name(n.name, where(ro.source, fmt::format("nodes[{}].name", n.origin.node)));
            n.name = distinct_track_name(n.name, names);  // two nodes of one name: "<name>.2"
            tracks.push_back(std::move(n));
        }
    }
    if (tracks.empty())
        throw input_error(ro.source,
                          "no rotation, translation, scale or weights channels: expected an animation of a node's "
                          "rotation, translation, scale or morph weights");
    return tracks;
}

gltf_file load(std::istream& in, format f, const read_options& ro) {
    const std::filesystem::path directory = std::filesystem::path(ro.source).parent_path();
    return load_gltf(in, f, ro.source, directory.empty() ? "." : directory.string(), ro.max_bytes);
}

/// A glTF file's keys, track after track: each node's samplers are read
/// when its track's turn comes, so that one track's keys are held at a time.
class gltf_keys final : public key_reader {
public:
    gltf_keys(std::shared_ptr<gltf_source> loaded, const read_options& ro, warnings& warn)
        : loaded_(std::move(loaded)), file_(loaded_->file), tracks_(tracks_of(file_, ro, warn)), flags_(ro.settings) {}

    bool next(std::string& track, raw_key& k) override {
        while (key_ == times_.size()) {
            if (next_track_ == tracks_.size()) return false;
            begin(next_track_++);
        }
        track = tracks_[next_track_ - 1].name;
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
        full_spline_key s{};
        if (rotation_) {
            std::array<double, 4> v{}, in{}, out{};
            const std::size_t i = components_at(*rotation_, t, true, v, tangents(std::span(in)), tangents(std::span(out)));
            const bool key = i != between_keys;
            s.rotation = {v[0], v[1], v[2], v[3]};
            if (!key && rotation_->how == method::slerp && t > rotation_->times.front() && t < rotation_->times.back())
                s.rotation = slerp_at(*rotation_, t);
            s.rotation_in = {in[0], in[1], in[2], in[3]}, s.rotation_out = {out[0], out[1], out[2], out[3]};
            // A value the curve passes between keys is not unit (a spline's, at least): it counts as given normalised.
            const quat q = key || !(norm(s.rotation) > 0) ? s.rotation : normalized(s.rotation);
            raw.values = {q.w, q.x, q.y, q.z};
            // Where make_key may say something of the key (zero, or renormalised): formatted only then.
            // (|q|² is off 1 by more than |q| is: the square root only for a key that may be.)
            if (std::fabs(dot(q, q) - 1) > tol::unit_norm && std::fabs(norm(q) - 1) > tol::unit_norm) {
                const channel_curve& other = translation_ ? *translation_ : scale_ ? *scale_ : *weights_;
                raw.at.path = key ? fmt::format("{}.output[{}]", rotation_->path, i)
                                  : fmt::format("{}.input", other.path);
            }
        } else {
            if (std::fabs(norm(rest_) - 1) > tol::unit_norm) raw.at.path = fmt::format("nodes[{}].rotation", node_);
            raw.values = {rest_.w, rest_.x, rest_.y, rest_.z};
            s.rotation = rest_;
        }
        if (translation_) raw.translation = vector_at(*translation_, t, s.translation_in, s.translation_out);
        if (scale_) raw.scale = vector_at(*scale_, t, s.scale_in, s.scale_out);
        if (weights_) {
            // Held outside its keys, as glTF clamps: every key of the track has weights.
            const std::size_t n = weights_->width;
            raw.weights.resize(n);
            if (spline_) s.weights_in.resize(n), s.weights_out.resize(n);
            components_at(*weights_, t, true, raw.weights, s.weights_in, s.weights_out);
        }
        if (spline_) raw.spline = std::move(s);
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
            std::copy(in.begin(), in.end(), out.begin());
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
    return std::make_unique<gltf_keys>(std::make_shared<gltf_source>(gltf_source{load(in, f, ro), {}}), ro, warn);
}

std::unique_ptr<key_reader> make_gltf_reader(std::shared_ptr<gltf_source> loaded, const read_options& ro,
                                             warnings& warn) {
    return std::make_unique<gltf_keys>(std::move(loaded), ro, warn);
}

std::shared_ptr<gltf_source> read_gltf_source(std::istream& in, format f, const read_options& ro, warnings& warn) {
    auto source = std::make_shared<gltf_source>();
    source->file = load(in, f, ro);
    for (const node_track& n : tracks_of(source->file, ro, warn)) source->origins.push_back(n.origin);
    return source;
}

}  // namespace keyrot
