#include "io/gltf.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "io/gltf_file.hpp"
#include "keyrot/interpolate.hpp"
#include "keyrot/tolerances.hpp"

namespace keyrot {
namespace {

/// One sampler as its channels read it: key times, and per key the value
/// (and for CUBICSPLINE the in- and out-tangents), rotations in (w, x, y, z).
struct channel_curve {
    std::string path;  // "animations[0].samplers[2]", for messages
    std::vector<double> times;
    std::size_t width = 0;  // 4 for a rotation, 3 for a translation or scale
    method how = method::slerp;
    std::vector<double> values;  // per key: width values; CUBICSPLINE: in-tangent, value, out-tangent

    std::size_t keys() const { return times.size(); }
    const double* element(std::size_t key, int part) const {  // part: -1 in-tangent, 0 value, 1 out-tangent
        const std::size_t per_key = how == method::cubicspline ? 3 : 1;
        const std::size_t slot = how == method::cubicspline ? static_cast<std::size_t>(part + 1) : 0;
        return values.data() + (key * per_key + slot) * width;
    }
    std::array<double, 4> get(std::size_t key, int part) const {
        const double* e = element(key, part);
        return {e[0], e[1], e[2], width == 4 ? e[3] : 0};
    }
};

method method_of(const std::string& interpolation) {
    if (interpolation == "STEP") return method::step;
    if (interpolation == "CUBICSPLINE") return method::cubicspline;
    return method::slerp;
}

/// A sampler's input and output for a channel of `width` (4: rotation).
channel_curve read_sampler(gltf_file& file, const gltf_json& sampler, const std::string& path, std::size_t width) {
    channel_curve c{path, {}, width, method::slerp, {}};
    const std::string at = fmt::format("{}: {}", file.source, path);
    if (!sampler.is_object() || !sampler.contains("input") || !sampler.contains("output"))
        throw input_error(at, "expected an object with input and output");
    const std::string interpolation = string_member(sampler, "interpolation", "LINEAR", at);
    if (interpolation != "LINEAR" && interpolation != "STEP" && interpolation != "CUBICSPLINE")
        throw input_error(
            at, fmt::format("interpolation '{}': expected LINEAR, STEP or CUBICSPLINE", excerpt(interpolation)));
    c.how = method_of(interpolation);
    c.times = read_accessor(file, sampler["input"], path + ".input", {"SCALAR", false});
    for (std::size_t i = 1; i < c.times.size(); ++i)
        if (!(c.times[i] > c.times[i - 1]))
            throw input_error(at + ".input", fmt::format("time {} s at key {} is not after the previous key's {} s: "
                                                         "expected strictly increasing times",
                                                         c.times[i], i, c.times[i - 1]));
    c.values = read_accessor(file, sampler["output"], path + ".output", {width == 4 ? "VEC4" : "VEC3", true});
    const std::size_t per_key = c.how == method::cubicspline ? 3 : 1;
    if (c.values.size() != c.keys() * per_key * width)
        throw input_error(at + ".output",
                          fmt::format("{} elements for {} key times: expected {}{}", c.values.size() / width, c.keys(),
                                      c.keys() * per_key,
                                      per_key == 3 ? " (CUBICSPLINE: in-tangent, value, out-tangent per key)" : ""));
    if (c.how == method::cubicspline && c.keys() < 2)
        throw input_error(at, "CUBICSPLINE with one key: expected at least two");
    if (width == 4)  // glTF stores x, y, z, w; keyrot's order is w, x, y, z
        for (std::size_t i = 0; i < c.values.size(); i += 4) {
            const double w = c.values[i + 3];
            c.values[i + 3] = c.values[i + 2], c.values[i + 2] = c.values[i + 1], c.values[i + 1] = c.values[i];
            c.values[i] = w;
        }
    return c;
}

/// The curve's value at `time` within its keys (and, for CUBICSPLINE, its
/// derivative per second there), as the specification interpolates it:
/// LINEAR rotations by slerp the short way, translations and scales by lerp.
std::pair<std::array<double, 4>, std::array<double, 4>> evaluate(const channel_curve& c, double time) {
    // Outside its keys a channel holds its first or last value (as glTF clamps).
    if (time <= c.times.front()) return {c.get(0, 0), {}};
    if (time >= c.times.back()) return {c.get(c.keys() - 1, 0), {}};
    const std::size_t i =
        static_cast<std::size_t>(std::upper_bound(c.times.begin(), c.times.end(), time) - c.times.begin()) - 1;
    if (c.times[i] == time || c.how == method::step) return {c.get(i, 0), {}};
    const double seconds = c.times[i + 1] - c.times[i], h = (time - c.times[i]) / seconds;
    if (c.how == method::cubicspline) {
        const auto v0 = c.get(i, 0), b0 = c.get(i, 1), v1 = c.get(i + 1, 0), a1 = c.get(i + 1, -1);
        // The derivative of hermite() by s, over the interval: per second.
        const double h2 = h * h;
        std::array<double, 4> d{};
        for (std::size_t j = 0; j < 4; ++j)
            d[j] = ((6 * h2 - 6 * h) * v0[j] + (6 * h - 6 * h2) * v1[j]) / seconds + (3 * h2 - 4 * h + 1) * b0[j] +
                   (3 * h2 - 2 * h) * a1[j];
        return {hermite(v0, b0, v1, a1, seconds, h), d};
    }
    const auto a = c.get(i, 0), b = c.get(i + 1, 0);
    if (c.width == 3) return {{(1 - h) * a[0] + h * b[0], (1 - h) * a[1] + h * b[1], (1 - h) * a[2] + h * b[2], 0}, {}};
    const quat qa = normalized({a[0], a[1], a[2], a[3]});
    quat qb = normalized({b[0], b[1], b[2], b[3]});
    if (dot(qa, qb) < 0) qb = -qb;
    const quat q = slerp(qa, qb, h);
    return {{q.w, q.x, q.y, q.z}, {}};
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
    const std::string at = fmt::format("{}: nodes[{}].rotation", file.source, node);
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

/// Animation `a`'s rotation, translation and scale channels, by node in the order
/// of their first channel. Other channels are noted and left out.
std::vector<node_track> channels_of(const gltf_file& file, std::size_t a, warnings& warn) {
    const gltf_json& anim = top_array(file, "animations")[a];
    const std::string path = fmt::format("animations[{}]", a);
    const std::string at = fmt::format("{}: {}", file.source, path);
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
        if (what != "rotation" && what != "translation" && what != "scale") {
            warn.once("gltf-" + what, fmt::format("{} channels are not read: keyrot reads rotation, translation and "
                                                  "scale channels (first at {}.channels[{}])",
                                                  excerpt(what.empty() ? "unnamed" : what), path, c));
            continue;
        }
        if (!ch["sampler"].is_number_unsigned() || ch["sampler"].get<std::size_t>() >= samplers.size())
            throw input_error(here + ".sampler", fmt::format("{}: expected an index into {}.samplers",
                                                             excerpt(ch["sampler"].dump()), path));
        const auto [it, added] = index.emplace(node, nodes.size());
        if (added) nodes.push_back({{a, node, std::nullopt, std::nullopt, std::nullopt}, {}});
        gltf_track_origin& o = nodes[it->second].origin;
        auto& slot = what == "rotation" ? o.rotation : what == "translation" ? o.translation : o.scale;
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
            check_track_name(n.name, fmt::format("{}: nodes[{}].name", ro.source, n.origin.node));
            n.name = distinct_track_name(n.name, names);  // two nodes of one name: "<name>.2"
            tracks.push_back(std::move(n));
        }
    }
    if (tracks.empty())
        throw input_error(ro.source,
                          "no rotation, translation or scale channels: expected an animation of a node's "
                          "rotation, translation or scale");
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
    gltf_keys(std::istream& in, format f, const read_options& ro, warnings& warn)
        : file_(load(in, f, ro)), tracks_(tracks_of(file_, ro, warn)), flags_(ro.settings) {}

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
        const auto read = [&](std::optional<std::size_t> channel, std::size_t width) -> std::optional<channel_curve> {
            if (!channel) return std::nullopt;
            const std::size_t s = anim["channels"][*channel]["sampler"];
            return read_sampler(file_, anim["samplers"][s], fmt::format("animations[{}].samplers[{}]", o.animation, s),
                                width);
        };
        rotation_ = read(o.rotation, 4);
        translation_ = read(o.translation, 3);
        scale_ = read(o.scale, 3);
        times_.clear();
        spline_ = false;
        for (const std::optional<channel_curve>* c : {&rotation_, &translation_, &scale_}) {
            if (!*c) continue;
            times_.insert(times_.end(), (*c)->times.begin(), (*c)->times.end());
            spline_ = spline_ || (*c)->how == method::cubicspline;
        }
        std::sort(times_.begin(), times_.end());
        times_.erase(std::unique(times_.begin(), times_.end()), times_.end());
        rest_ = rotation_ ? quat{} : rest_rotation(file_, o.node);
        node_ = o.node;
        settings_ = flags_;
        const auto how = [](const std::optional<channel_curve>& c, method absent) { return c ? c->how : absent; };
        settings_.interpolation = track_interpolation{how(rotation_, method::step), how(translation_, method::slerp),
                                                      how(scale_, method::slerp), 0x1p-24};
        key_ = 0;
    }

    /// Key j of the current track into `raw` (raw_key::reset): each
    /// channel's key there, or its curve's value.
    void key_at(std::size_t j, raw_key& raw) const {
        const double t = times_[j];
        raw.reset();
        raw.time = t;
        spline_key s{};
        if (rotation_) {
            const auto key = std::lower_bound(rotation_->times.begin(), rotation_->times.end(), t);
            const bool keyed = key != rotation_->times.end() && *key == t;
            const std::size_t i = static_cast<std::size_t>(key - rotation_->times.begin());
            std::array<double, 4> v{};
            if (keyed) {
                v = rotation_->get(i, 0);
                if (rotation_->how == method::cubicspline) {
                    // The first key's in-tangent and the last's out-tangent do nothing in glTF; zero, they
                    // keep the rotation held where the translation's keys reach beyond it.
                    const bool held_before = i == 0 && times_.front() < t,
                               held_after = i + 1 == rotation_->keys() && times_.back() > t;
                    const auto in = held_before ? std::array<double, 4>{} : rotation_->get(i, -1);
                    const auto out = held_after ? std::array<double, 4>{} : rotation_->get(i, 1);
                    s.rotation_in = {in[0], in[1], in[2], in[3]}, s.rotation_out = {out[0], out[1], out[2], out[3]};
                }
            } else {
                const auto [value, slope] = evaluate(*rotation_, t);
                v = value;
                s.rotation_in = s.rotation_out = {slope[0], slope[1], slope[2], slope[3]};
            }
            s.rotation = {v[0], v[1], v[2], v[3]};
            // A value the curve passes between keys is not unit (a spline's, at least): it counts as given normalised.
            const quat q = keyed || !(norm(s.rotation) > 0) ? s.rotation : normalized(s.rotation);
            raw.values = {q.w, q.x, q.y, q.z};
            // Where make_key may say something of the key (zero, or renormalised): formatted only then.
            if (std::fabs(norm(q) - 1) > tol::unit_norm)
                raw.at.path = keyed ? fmt::format("{}.output[{}]", rotation_->path, i)
                                    : fmt::format("{}.input", (translation_ ? translation_ : scale_)->path);
        } else {
            if (std::fabs(norm(rest_) - 1) > tol::unit_norm) raw.at.path = fmt::format("nodes[{}].rotation", node_);
            raw.values = {rest_.w, rest_.x, rest_.y, rest_.z};
            s.rotation = rest_;
        }
        if (translation_) raw.translation = vector_at(*translation_, t, s.translation_in, s.translation_out);
        if (scale_) raw.scale = vector_at(*scale_, t, s.scale_in, s.scale_out);
        if (spline_) raw.spline = s;
    }

    /// A translation or scale channel at time `t`, with its tangents there:
    /// its key, or its curve's value; nothing outside its keys (it is held).
    static std::optional<vec3> vector_at(const channel_curve& c, double t, vec3& in, vec3& out) {
        if (t < c.times.front() || t > c.times.back()) return std::nullopt;
        const auto key = std::lower_bound(c.times.begin(), c.times.end(), t);
        const std::size_t i = static_cast<std::size_t>(key - c.times.begin());
        std::array<double, 4> v{}, before{}, after{};
        if (*key == t) {
            v = c.get(i, 0);
            if (c.how == method::cubicspline) before = c.get(i, -1), after = c.get(i, 1);
        } else {
            std::tie(v, before) = evaluate(c, t);
            after = before;
        }
        in = {before[0], before[1], before[2]}, out = {after[0], after[1], after[2]};
        return vec3{v[0], v[1], v[2]};
    }

    gltf_file file_;
    std::vector<node_track> tracks_;
    key_settings flags_, settings_;
    std::size_t next_track_ = 0, key_ = 0, node_ = 0;
    std::optional<channel_curve> rotation_, translation_, scale_;
    std::vector<double> times_;
    bool spline_ = false;
    quat rest_;
};

}  // namespace

std::unique_ptr<key_reader> make_gltf_reader(std::istream& in, format f, const read_options& ro, warnings& warn) {
    return std::make_unique<gltf_keys>(in, f, ro, warn);
}

std::shared_ptr<gltf_source> read_gltf_source(std::istream& in, format f, const read_options& ro, warnings& warn) {
    auto source = std::make_shared<gltf_source>();
    source->file = load(in, f, ro);
    for (const node_track& n : tracks_of(source->file, ro, warn)) source->origins.push_back(n.origin);
    return source;
}

}  // namespace keyrot
