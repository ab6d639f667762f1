// SPDX-License-Identifier: MIT
#include "io/gltf/gltf_tracks.hpp"

#include <fmt/format.h>

#include <map>
#include <set>

namespace keyrot {
namespace {

std::string node_name(const gltf_file& file, std::size_t node) {
    const gltf_json& n = top_array(file, "nodes")[node];
    if (n.is_object() && n.contains("name") && n["name"].is_string() && !n["name"].get<std::string>().empty())
        return n["name"];
    return fmt::format("node{}", node);
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

}  // namespace

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

}  // namespace keyrot
