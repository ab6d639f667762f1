#include "io/gltf.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "io/gltf_file.hpp"
#include "keyrot/interpolate.hpp"

namespace keyrot {
namespace {

/// One sampler as its channels read it: key times, and per key the value
/// (and for CUBICSPLINE the in- and out-tangents), rotations in (w, x, y, z).
struct channel_curve {
    std::string path;  // "animations[0].samplers[2]", for messages
    std::vector<double> times;
    std::size_t width = 0;  // 4 for a rotation, 3 for a translation
    method how = method::slerp;
    std::vector<double> values;  // per key: width values; CUBICSPLINE: in-tangent, value, out-tangent

    std::size_t keys() const { return times.size(); }
    const double* element(std::size_t key, int part) const {  // part: -1 in-tangent, 0 value, 1 out-tangent
        const std::size_t per_key = how == method::cubicspline ? 3 : 1;
        const std::size_t slot = how == method::cubicspline ? static_cast<std::size_t>(part + 1) : 0;
        return values.data() + (key * per_key + slot) * width;
    }
    std::array<double, 4> get(std::size_t key, int part) const {
        std::array<double, 4> v{};
        std::copy_n(element(key, part), width, v.begin());
        return v;
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
        throw input_error(at, fmt::format("interpolation '{}': expected LINEAR, STEP or CUBICSPLINE", excerpt(interpolation)));
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
        throw input_error(at + ".output", fmt::format("{} elements for {} key times: expected {}{}", c.values.size() / width,
                                                      c.keys(), c.keys() * per_key,
                                                      per_key == 3 ? " (CUBICSPLINE: in-tangent, value, out-tangent per key)" : ""));
    if (c.how == method::cubicspline && c.keys() < 2)
        throw input_error(at, "CUBICSPLINE with one key: expected at least two");
    if (width == 4)  // glTF stores x, y, z, w; keyrot's order is w, x, y, z
        for (std::size_t i = 0; i < c.values.size(); i += 4) std::rotate(&c.values[i], &c.values[i + 3], &c.values[i + 4]);
    return c;
}

/// The curve's value at `time` within its keys (and, for CUBICSPLINE, its
/// derivative per second there), as the specification interpolates it:
/// LINEAR rotations by slerp the short way, translations by lerp.
std::pair<std::array<double, 4>, std::array<double, 4>> evaluate(const channel_curve& c, double time) {
    // Outside its keys a channel holds its first or last value (as glTF clamps).
    if (time <= c.times.front()) return {c.get(0, 0), {}};
    if (time >= c.times.back()) return {c.get(c.keys() - 1, 0), {}};
    const std::size_t i = static_cast<std::size_t>(std::upper_bound(c.times.begin(), c.times.end(), time) - c.times.begin()) - 1;
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

/// A node's channels in one animation.
struct node_channels {
    gltf_track_origin origin;
    std::optional<channel_curve> rotation, translation;
};

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
    if (!r.is_array() || r.size() != 4 || !std::all_of(r.begin(), r.end(), [](const gltf_json& v) { return v.is_number(); }))
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
    throw input_error(file.source, fmt::format("--animation {}: no such animation: expected one of {} or an index 0 to {}",
                                               excerpt(*wanted), excerpt(fmt::format("{}", fmt::join(names, ", ")), 200),
                                               names.size() - 1));
}

std::string animation_name(const gltf_file& file, std::size_t a) {
    const gltf_json& anim = top_array(file, "animations")[a];
    if (anim.contains("name") && anim["name"].is_string() && !anim["name"].get<std::string>().empty()) return anim["name"];
    return fmt::format("animation{}", a);
}

/// Animation `a`'s rotation and translation channels, by node in the order
/// of their first channel. Other channels are noted and left out.
std::vector<node_channels> channels_of(gltf_file& file, std::size_t a, warnings& warn) {
    const gltf_json& anim = top_array(file, "animations")[a];
    const std::string path = fmt::format("animations[{}]", a);
    const std::string at = fmt::format("{}: {}", file.source, path);
    if (!anim.is_object() || !anim.contains("channels") || !anim["channels"].is_array() || !anim.contains("samplers") ||
        !anim["samplers"].is_array())
        throw input_error(at, "expected an object with channels and samplers");
    const gltf_json &channels = anim["channels"], &samplers = anim["samplers"];
    std::vector<node_channels> nodes;
    std::map<std::size_t, std::size_t> index;  // node -> its entry
    for (std::size_t c = 0; c < channels.size(); ++c) {
        const gltf_json& ch = channels[c];
        const std::string here = fmt::format("{}.channels[{}]", at, c);
        if (!ch.is_object() || !ch.contains("target") || !ch["target"].is_object() || !ch.contains("sampler"))
            throw input_error(here, "expected an object with a sampler and a target");
        const gltf_json& target = ch["target"];
        const std::string what = string_member(target, "path", "", here + ".target");
        if (!target.contains("node")) {
            warn.once("gltf-no-node", fmt::format("{}.channels[{}]: a channel without a node (an extension's) is left out",
                                                  path, c));
            continue;
        }
        const std::size_t node = index_into(file, target["node"], "nodes", here + ".target.node");
        if (what != "rotation" && what != "translation") {
            warn.once("gltf-" + what, fmt::format("{} channels are not read: keyrot reads rotation and translation "
                                                  "channels (first at {}.channels[{}])",
                                                  excerpt(what.empty() ? "unnamed" : what), path, c));
            continue;
        }
        if (!samplers.is_array() || !ch["sampler"].is_number_unsigned() || ch["sampler"].get<std::size_t>() >= samplers.size())
            throw input_error(here + ".sampler", fmt::format("{}: expected an index into {}.samplers", excerpt(ch["sampler"].dump()), path));
        const std::size_t s = ch["sampler"];
        const auto [it, added] = index.emplace(node, nodes.size());
        if (added) nodes.push_back({{a, node, std::nullopt, std::nullopt}, std::nullopt, std::nullopt});
        node_channels& n = nodes[it->second];
        auto& slot = what == "rotation" ? n.rotation : n.translation;
        if (slot) throw input_error(here, fmt::format("node {}'s {} is animated twice in one animation: expected once", node, what));
        (what == "rotation" ? n.origin.rotation : n.origin.translation) = c;
        slot = read_sampler(file, samplers[s], fmt::format("{}.samplers[{}]", path, s), what == "rotation" ? 4 : 3);
    }
    return nodes;
}

/// One node's channels as one track's keys.
track track_of(const gltf_file& file, const node_channels& n, std::string name, const read_options& ro, warnings& warn) {
    std::vector<double> times;
    for (const auto& c : {n.rotation, n.translation})
        if (c) times.insert(times.end(), c->times.begin(), c->times.end());
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    const bool spline = (n.rotation && n.rotation->how == method::cubicspline) ||
                        (n.translation && n.translation->how == method::cubicspline);
    const quat rest = n.rotation ? quat{} : rest_rotation(file, n.origin.node);
    track_builder builder(name, {}, ro.settings);
    std::vector<std::optional<spline_key>> splines;
    for (const double t : times) {
        raw_key raw;
        raw.time = t;
        raw.kind = rep::quat;
        spline_key s{};
        if (n.rotation) {
            const auto key = std::lower_bound(n.rotation->times.begin(), n.rotation->times.end(), t);
            const bool keyed = key != n.rotation->times.end() && *key == t;
            const std::size_t i = static_cast<std::size_t>(key - n.rotation->times.begin());
            raw.at.path = keyed ? fmt::format("{}.output[{}]", n.rotation->path, i) : fmt::format("{}.input", n.translation->path);
            std::array<double, 4> v{};
            if (keyed) {
                v = n.rotation->get(i, 0);
                if (n.rotation->how == method::cubicspline) {
                    // The first key's in-tangent and the last's out-tangent do nothing in glTF; zero, they
                    // keep the rotation held where the translation's keys reach beyond it.
                    const bool held_before = i == 0 && times.front() < t, held_after = i + 1 == n.rotation->keys() && times.back() > t;
                    const auto in = held_before ? std::array<double, 4>{} : n.rotation->get(i, -1);
                    const auto out = held_after ? std::array<double, 4>{} : n.rotation->get(i, 1);
                    s.rotation_in = {in[0], in[1], in[2], in[3]}, s.rotation_out = {out[0], out[1], out[2], out[3]};
                }
            } else {
                const auto [value, slope] = evaluate(*n.rotation, t);
                v = value;
                s.rotation_in = s.rotation_out = {slope[0], slope[1], slope[2], slope[3]};
            }
            s.rotation = {v[0], v[1], v[2], v[3]};
            // A value the curve passes between keys is not unit (a spline's, at least): it counts as given normalised.
            const quat q = keyed || !(norm(s.rotation) > 0) ? s.rotation : normalized(s.rotation);
            raw.values = {q.w, q.x, q.y, q.z};
        } else {
            raw.at.path = fmt::format("nodes[{}].rotation", n.origin.node);
            raw.values = {rest.w, rest.x, rest.y, rest.z};
            s.rotation = rest;
        }
        if (n.translation && t >= n.translation->times.front() && t <= n.translation->times.back()) {
            const auto key = std::lower_bound(n.translation->times.begin(), n.translation->times.end(), t);
            const std::size_t i = static_cast<std::size_t>(key - n.translation->times.begin());
            std::array<double, 4> v{}, in{}, out{};
            if (*key == t) {
                v = n.translation->get(i, 0);
                if (n.translation->how == method::cubicspline) in = n.translation->get(i, -1), out = n.translation->get(i, 1);
            } else {
                std::tie(v, in) = evaluate(*n.translation, t);
                out = in;
            }
            raw.translation = vec3{v[0], v[1], v[2]};
            s.translation_in = {in[0], in[1], in[2]}, s.translation_out = {out[0], out[1], out[2]};
        }
        builder.add(raw, warn);
        splines.push_back(spline ? std::optional(s) : std::nullopt);
    }
    track result = std::move(builder).finish(warn);
    for (std::size_t i = 0; i < result.keys.size(); ++i) result.keys[i].spline = splines[i];
    result.interpolation = track_interpolation{n.rotation ? n.rotation->how : method::step,
                                               n.translation ? n.translation->how : method::slerp, 0x1p-24};
    return result;
}

}  // namespace

document read_gltf(std::istream& in, format f, const read_options& ro, warnings& warn) {
    const std::filesystem::path directory = std::filesystem::path(ro.source).parent_path();
    gltf_file file = load_gltf(in, f, ro.source, directory.empty() ? "." : directory.string(), ro.max_bytes);
    const std::vector<std::size_t> animations = chosen_animations(file, ro.animation);
    auto source = std::make_shared<gltf_source>();
    document doc{ro.source, f, true, {}, source};
    std::set<std::string> names;
    for (const std::size_t a : animations) {
        for (const node_channels& n : channels_of(file, a, warn)) {
            std::string name = node_name(file, n.origin.node);
            if (animations.size() > 1) name = animation_name(file, a) + "/" + name;
            if (names.contains(name)) name += fmt::format("#node{}", n.origin.node);  // two nodes of one name
            check_track_name(name, fmt::format("{}: nodes[{}].name", ro.source, n.origin.node));
            names.insert(name);
            doc.tracks.push_back(track_of(file, n, name, ro, warn));
            source->origins.push_back(n.origin);
        }
    }
    if (doc.tracks.empty())
        throw input_error(ro.source, "no rotation or translation channels: expected an animation of a node's rotation "
                                     "or translation");
    source->file = std::move(file);
    return doc;
}

}  // namespace keyrot
