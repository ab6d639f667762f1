// SPDX-License-Identifier: MIT
#include "io/gltf/gltf_write.hpp"

#include <fmt/format.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <tuple>

#include "io/common/output.hpp"
#include "io/gltf/gltf_buffer.hpp"
#include "io/gltf/gltf_rows.hpp"

namespace keyrot {
namespace {

using namespace detail;

/// Extensions whose references to accessors and bufferViews this writer
/// renumbers, or which hold none, beyond harmless_extension's: a file that
/// uses any other is not rewritten, since an index it holds could come to
/// name the wrong data.
const std::set<std::string, std::less<>> renumbered_extensions = {"EXT_lights_image_based",
                                                                  "EXT_mesh_gpu_instancing",
                                                                  "KHR_animation_pointer",
                                                                  "KHR_draco_mesh_compression",
                                                                  "KHR_materials_anisotropy",
                                                                  "KHR_materials_dispersion",
                                                                  "KHR_materials_pbrSpecularGlossiness",
                                                                  "KHR_xmp_json_ld",
                                                                  "MSFT_lod",
                                                                  "MSFT_texture_dds"};

/// Calls f on each member of `j` at `path` (names; "*" for every element
/// or member) that exists.
template <class F>
void at_path(gltf_json& j, std::initializer_list<const char*> path, F&& f) {
    const auto walk = [&](auto& self, gltf_json& here, const char* const* step, const char* const* end) -> void {
        if (step == end) return f(here);
        if (std::strcmp(*step, "*") == 0) {
            if (here.is_array() || here.is_object())
                for (auto& element : here) self(self, element, step + 1, end);
        } else if (here.is_object()) {
            if (const auto it = here.find(*step); it != here.end()) self(self, *it, step + 1, end);
        }
    };
    walk(walk, j, path.begin(), path.end());
}

/// f(reference) for every reference to an accessor the writer knows of.
template <class F>
void accessor_refs(gltf_json& j, F&& f) {
    at_path(j, {"meshes", "*", "primitives", "*", "attributes", "*"}, f);
    at_path(j, {"meshes", "*", "primitives", "*", "indices"}, f);
    at_path(j, {"meshes", "*", "primitives", "*", "targets", "*", "*"}, f);
    at_path(j, {"skins", "*", "inverseBindMatrices"}, f);
    at_path(j, {"animations", "*", "samplers", "*", "input"}, f);
    at_path(j, {"animations", "*", "samplers", "*", "output"}, f);
    at_path(j, {"nodes", "*", "extensions", "EXT_mesh_gpu_instancing", "attributes", "*"}, f);
}

/// f(reference) for every reference to a bufferView the writer knows of.
template <class F>
void view_refs(gltf_json& j, F&& f) {
    at_path(j, {"accessors", "*", "bufferView"}, f);
    at_path(j, {"accessors", "*", "sparse", "indices", "bufferView"}, f);
    at_path(j, {"accessors", "*", "sparse", "values", "bufferView"}, f);
    at_path(j, {"images", "*", "bufferView"}, f);
    at_path(j, {"meshes", "*", "primitives", "*", "extensions", "KHR_draco_mesh_compression", "bufferView"}, f);
}

/// Keeps the elements of top-level array `name` whose index `keep` holds,
/// and renumbers the references `refs` visits.
template <class Refs>
void compact(gltf_json& j, const char* name, const std::vector<bool>& keep, Refs&& refs) {
    std::vector<std::size_t> renumbered(keep.size(), 0);
    gltf_json array = gltf_json::array();
    for (std::size_t i = 0; i < keep.size(); ++i)
        if (keep[i]) renumbered[i] = array.size(), array.push_back(std::move(j[name][i]));
    refs(j, [&](gltf_json& ref) {
        if (ref.is_number_unsigned() && ref.get<std::size_t>() < keep.size()) ref = renumbered[ref.get<std::size_t>()];
    });
    if (array.empty())
        j.erase(name);
    else
        j[name] = std::move(array);
}

/// Whether every key of `values` (`width` floats each) is the first, bit for bit.
bool constant(const std::vector<float>& values, std::size_t width) {
    for (std::size_t i = width; i < values.size(); ++i)
        if (std::bit_cast<std::uint32_t>(values[i]) != std::bit_cast<std::uint32_t>(values[i % width])) return false;
    return true;
}

/// What a rewritten file's new samplers share: an accessor for each list
/// of key times (as 32-bit floats), one for each value of a single key (with
/// its element's width), and per animation a sampler for each (input,
/// output, interpolation).
struct shared_parts {
    std::map<std::vector<float>, std::size_t> inputs;
    std::map<std::pair<std::size_t, std::vector<float>>, std::size_t> single_values;
    std::map<std::pair<std::size_t, std::tuple<std::size_t, std::size_t, std::string>>, std::size_t> samplers;
};

/// A sampler of track `t`'s channel `path` into animation `a`; returns its
/// index. What another sampler already has is shared (`shared`). With
/// `collapse` (the track's rotation is written, on every key of the
/// track), a translation, scale or weights channel on the rotation's times
/// whose values never change (as 32-bit floats), LINEAR or STEP, is written
/// as its first key alone: glTF holds a sampler's value beyond its keys,
/// and keyrot reads a key that is alone at every key of its track. A
/// rotation stored as normalised 16-bit integers (gathered_rows) is written so.
std::size_t add_sampler(buffer_builder& b, gltf_json& json, std::size_t a, const stored_track& t, gltf_path path,
                        shared_parts& shared, bool collapse) {
    const stored_channel& c = t.channel(path);
    for (const std::exception_ptr& bad : {c.bad_time, c.bad_value})
        if (bad) std::rethrow_exception(bad);
    const method how = t.how_of(path);
    const bool vectors = path != gltf_path::rotation, spline = how == method::cubicspline;
    const bool shorts = !c.shorts.empty();
    const bool one_key =
        collapse && vectors && !spline && c.times.size() == t.rows && constant(c.values, c.width);
    std::vector<float> first_time, first_value;
    if (one_key) {
        first_time = {c.times.front()};
        first_value.assign(c.values.begin(), c.values.begin() + static_cast<std::ptrdiff_t>(c.width));
    }
    const std::vector<float>& key_times = one_key ? first_time : c.times;
    const std::vector<float>& values = one_key ? first_value : c.values;
    auto input = shared.inputs.find(key_times);
    if (input == shared.inputs.end()) input = shared.inputs.emplace(key_times, b.accessor(key_times, 1, true)).first;
    // (weights are SCALAR, a weight per morph target in each key's element)
    const std::size_t width = !vectors ? 4 : path == gltf_path::weights ? 1 : 3;
    std::size_t output;
    if (shorts) {
        output = b.accessor(c.shorts, c.times.size(), width, component::normalized_short);
    } else if (key_times.size() == 1) {
        auto single = shared.single_values.find({width, values});
        if (single == shared.single_values.end())
            single = shared.single_values.emplace(std::pair(width, values), b.accessor(values, width, false)).first;
        output = single->second;
    } else {
        output = b.accessor(values, width, false);
    }
    const auto [sampler, made] = shared.samplers.try_emplace(
        {a, {input->second, output, interpolation_name(how)}}, json["animations"][a]["samplers"].size());
    if (made)
        json["animations"][a]["samplers"].push_back(
            {{"input", input->second}, {"interpolation", interpolation_name(how)}, {"output", output}});
    return sampler->second;
}

/// The input file with the samplers of the channels keyrot read replaced.
void rewrite(const std::vector<stored_track>& tracks, gltf_source& source, buffer_builder& b, gltf_json& json,
             warnings& warn) {
    gltf_file& file = source.file;
    for (const auto& name : json.value("extensionsUsed", gltf_json::array()))
        if (!name.is_string() ||
            !(harmless_extension(name.get<std::string>()) || renumbered_extensions.contains(name.get<std::string>())))
            throw input_error(file.source,
                              fmt::format("extensionsUsed: {} may refer to data keyrot would move: expected "
                                          "a file without it, or output in another format",
                                          excerpt(name.dump())));
    // Replaced channels: (animation, channel) -> (track, path).
    std::map<std::pair<std::size_t, std::size_t>, std::pair<std::size_t, gltf_path>> replaced;
    for (std::size_t i = 0; i < tracks.size(); ++i) {
        const gltf_track_origin& o = source.tracks[i].origin;
        if (o.rotation) replaced[{o.animation, *o.rotation}] = {i, gltf_path::rotation};
        if (o.translation) replaced[{o.animation, *o.translation}] = {i, gltf_path::translation};
        if (o.scale) replaced[{o.animation, *o.scale}] = {i, gltf_path::scale};
        if (o.weights) replaced[{o.animation, *o.weights}] = {i, gltf_path::weights};
    }
    // The old samplers of replaced channels leave; kept ones are renumbered.
    std::vector<bool> dropped_accessor(top_array(file, "accessors").size(), false);
    std::set<std::size_t> animations;
    for (const auto& [at, track] : replaced) animations.insert(at.first);
    std::size_t kept_channels = 0;
    for (const std::size_t a : animations) {
        gltf_json& anim = json["animations"][a];
        std::vector<bool> keep(anim["samplers"].size(), false);
        for (std::size_t c = 0; c < anim["channels"].size(); ++c) {
            if (replaced.contains({a, c})) continue;
            const gltf_json& sampler =
                anim["channels"][c]["sampler"];  // (the reader checked each channel is an object)
            if (!sampler.is_number_unsigned() || sampler.get<std::size_t>() >= keep.size())
                throw input_error(
                    where(file.source, fmt::format("animations[{}].channels[{}].sampler", a, c)),
                    fmt::format("{}: expected an index into animations[{}].samplers", excerpt(sampler.dump()), a));
            keep[sampler.get<std::size_t>()] = true;
            ++kept_channels;
        }
        gltf_json samplers = gltf_json::array();
        std::vector<std::size_t> renumbered(keep.size(), 0);
        for (std::size_t s = 0; s < keep.size(); ++s) {
            if (keep[s]) {
                renumbered[s] = samplers.size();
                samplers.push_back(anim["samplers"][s]);
            } else if (const gltf_json& old = anim["samplers"][s]; old.is_object()) {  // (not one no channel used)
                for (const char* end : {"input", "output"})
                    if (const auto ref = old.find(end); ref != old.end() && ref->is_number_unsigned() &&
                                                        ref->get<std::size_t>() < dropped_accessor.size())
                        dropped_accessor[ref->get<std::size_t>()] = true;
            }
        }
        for (std::size_t c = 0; c < anim["channels"].size(); ++c)
            if (!replaced.contains({a, c}))
                anim["channels"][c]["sampler"] = renumbered[anim["channels"][c]["sampler"].get<std::size_t>()];
        anim["samplers"] = std::move(samplers);
    }
    if (kept_channels)
        warn.once("gltf-kept",
                  fmt::format("{} channel{} keyrot does not read kept as {} were",
                              kept_channels, kept_channels == 1 ? "" : "s", kept_channels == 1 ? "it" : "they"));
    // An accessor still referred to stays (another sampler, a mesh may share it).
    accessor_refs(json, [&](gltf_json& ref) {
        if (ref.is_number_unsigned() && ref.get<std::size_t>() < dropped_accessor.size())
            dropped_accessor[ref.get<std::size_t>()] = false;
    });
    std::vector<bool> keep_accessor(dropped_accessor.size());
    for (std::size_t i = 0; i < keep_accessor.size(); ++i) keep_accessor[i] = !dropped_accessor[i];
    // The bufferViews only dropped accessors used leave with them.
    std::vector<bool> dropped_view(top_array(file, "bufferViews").size(), false);
    for (std::size_t i = 0; i < dropped_accessor.size(); ++i)
        if (dropped_accessor[i]) {
            gltf_json one = {{"accessors", gltf_json::array({json["accessors"][i]})}};
            view_refs(one, [&](gltf_json& ref) {
                if (ref.is_number_unsigned() && ref.get<std::size_t>() < dropped_view.size())
                    dropped_view[ref.get<std::size_t>()] = true;
            });
        }
    compact(json, "accessors", keep_accessor, [](gltf_json& j, auto&& f) { accessor_refs(j, f); });
    view_refs(json, [&](gltf_json& ref) {
        if (ref.is_number_unsigned() && ref.get<std::size_t>() < dropped_view.size())
            dropped_view[ref.get<std::size_t>()] = false;
    });
    std::vector<bool> keep_view(dropped_view.size());
    for (std::size_t i = 0; i < keep_view.size(); ++i) keep_view[i] = !dropped_view[i];
    // The kept views' bytes, from whichever buffer, into the one buffer of the output.
    compact(json, "bufferViews", keep_view, [](gltf_json& j, auto&& f) { view_refs(j, f); });
    const gltf_json views = json.contains("bufferViews") ? std::move(json["bufferViews"]) : gltf_json::array();
    json.erase("bufferViews");
    for (std::size_t v = 0; v < views.size(); ++v) {
        const std::string where = keyrot::where(file.source, fmt::format("bufferViews[{}]", v));
        if (!views[v].is_object() || !views[v].contains("buffer"))
            throw input_error(where, "expected an object with a buffer");
        const std::size_t buffer = index_into(file, views[v]["buffer"], "buffers", where);
        const std::string_view bytes = buffer_bytes(file, buffer);
        const std::size_t offset = unsigned_member(views[v], "byteOffset", 0, where);
        const std::size_t length = unsigned_member(views[v], "byteLength", 0, where);
        if (offset > bytes.size() || length > bytes.size() - offset)
            throw input_error(
                where, fmt::format("bytes {} to {} read past the end of buffer {}", offset, offset + length, buffer));
        // At the same offset modulo 4, so that the accessors in it stay aligned.
        gltf_json& view = json["bufferViews"][b.view(bytes.substr(offset, length), offset % 4)];
        const gltf_json placed = view["byteOffset"];
        view = views[v];
        view["buffer"] = 0;
        view["byteOffset"] = placed;
    }
    // The new samplers and channels.
    shared_parts shared;
    b.begin_shared_view();
    for (const auto& [at, who] : replaced) {
        const auto [a, c] = at;
        const auto [i, path] = who;
        const bool collapse = source.tracks[i].origin.rotation.has_value();
        const std::size_t sampler = add_sampler(b, json, a, tracks[i], path, shared, collapse);
        json["animations"][a]["channels"][c]["sampler"] = sampler;
    }
    b.end_shared_view();
}

/// Relative image URIs of the input, made relative to where the output goes.
void move_image_uris(gltf_json& json, const std::string& from_directory, const std::optional<std::string>& target) {
    const std::filesystem::path to =
        target ? std::filesystem::absolute(*target).parent_path() : std::filesystem::current_path();
    at_path(json, {"images", "*", "uri"}, [&](gltf_json& uri) {
        if (!uri.is_string()) return;
        const std::string u = uri;
        if (u.starts_with("data:") || u.find("://") != std::string::npos || u.starts_with("/")) return;
        const auto moved = std::filesystem::absolute(std::filesystem::path(from_directory) / u).lexically_relative(to);
        if (!moved.empty()) uri = moved.generic_string();
    });
}

/// A glTF input's tracks gathered, and written at finish() as that file
/// with the samplers of the channels keyrot read replaced.
class rewritten_table final : public gathered_rows {
public:
    rewritten_table(format f, const std::optional<std::string>& target, std::ostream& out, commit_mode commit,
                    bool short_rotations, std::shared_ptr<gltf_source> input, warnings& warn)
        : gathered_rows(short_rotations, warn.source()), f_(f), target_(target), commit_(commit), out_(out),
          input_(std::move(input)), warn_(warn) {}
    std::unique_ptr<table_output> track_apart() override {
        return std::make_unique<gathered_apart>(short_rotations_, source_, tracks_);
    }
    void finish() override {
        gltf_json json = input_->file.json;
        buffer_builder b(json, warn_.source());
        gltf_json buffer = gltf_json::object();
        if (const auto& buffers = top_array(input_->file, "buffers"); !buffers.empty() && buffers[0].is_object())
            buffer = buffers[0];
        try {
            rewrite(tracks_, *input_, b, json, warn_);
        } catch (const gltf_json::exception& e) {  // a part of the file keyrot did not read, of a type it did not expect
            throw input_error(input_->file.source, fmt::format("cannot rewrite this file: {}", e.what()));
        }
        move_image_uris(json, input_->file.directory, target_);
        buffer.erase("uri");
        json["buffers"] = gltf_json::array({buffer});
        put_file(json, b.bin, f_, target_, commit_, out_);
    }

private:
    format f_;
    std::optional<std::string> target_;
    commit_mode commit_;
    std::ostream& out_;
    std::shared_ptr<gltf_source> input_;
    warnings& warn_;
};

}  // namespace

std::unique_ptr<table_output> make_gltf_table(format f, const std::optional<std::string>& target, std::ostream& out,
                                              commit_mode commit, bool short_rotations,
                                              std::shared_ptr<gltf_source> source, std::vector<gltf_node> skeleton,
                                              warnings& warn) {
    if (source)
        return std::make_unique<rewritten_table>(f, target, out, commit, short_rotations, std::move(source), warn);
    return make_new_gltf_file(f, target, out, commit, short_rotations, std::move(skeleton), warn);
}

}  // namespace keyrot
