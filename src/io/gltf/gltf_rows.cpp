// SPDX-License-Identifier: MIT
#include "io/gltf/gltf_rows.hpp"

#include <fmt/format.h>

#include <array>
#include <utility>

namespace keyrot::detail {
namespace {

/// A quaternion's components in glTF's order, and a vector's.
std::array<double, 4> xyzw(const quat& q) { return {q.x, q.y, q.z, q.w}; }
std::array<double, 3> xyz(const vec3& v) { return {v.x, v.y, v.z}; }

}  // namespace

void gathered_rows::begin_track(const std::string& name, channels, const track_interpolation& written) {
    stored_track& t = tracks_.emplace_back();
    t.name = name, t.how = written;
    if (tracks_.size() < 2) return;
    // A rig's tracks are as long as each other: room for as many rows as the track before had.
    const stored_track& before = tracks_[tracks_.size() - 2];
    for (const auto& [c, b] : {std::pair(&t.rotation, &before.rotation),
                               std::pair(&t.translation, &before.translation), std::pair(&t.scale, &before.scale)})
        c->times.reserve(b->times.size()), c->values.reserve(b->values.size()), c->shorts.reserve(b->shorts.size());
}

void gathered_rows::row(const table_row& s) {
    stored_track& t = tracks_.back();
    ++t.rows;
    const auto where = [&] {
        return t.name.empty() ? source_ : keyrot::where(source_, fmt::format("track '{}'", t.name));
    };
    static const full_spline_key none{};  // the tangents of a row that is no CUBICSPLINE key: none
    const full_spline_key& spline = s.spline ? *s.spline : none;
    t.rotation.add(s.time, where, [&] {
        if (t.how.rotation == method::cubicspline)  // (floats: tangents are no unit quaternions)
            for (const quat& q : {spline.rotation_in, spline.rotation, spline.rotation_out})
                t.rotation.put(xyzw(q), where, "rotation");
        else if (short_rotations_)
            append_normalized_shorts(t.rotation.shorts, xyzw(s.rotation));
        else
            t.rotation.put(xyzw(s.rotation), where, "rotation");
    });
    const auto put = [&](stored_channel& c, const std::optional<vec3>& value, method how, const char* what,
                         const vec3& in, const vec3& out) {
        if (!value) return;
        c.add(s.time, where, [&] {
            if (how == method::cubicspline) c.put(xyz(in), where, what);
            c.put(xyz(*value), where, what);
            if (how == method::cubicspline) c.put(xyz(out), where, what);
        });
    };
    put(t.translation, s.translation, t.how.translation, "translation", spline.translation_in,
        spline.translation_out);
    put(t.scale, s.scale, t.how.scale, "scale", spline.scale_in, spline.scale_out);
    if (!s.weights.empty()) {
        stored_channel& w = t.weights;
        w.width = s.weights.size();
        const auto tangent = [&](const morph_weights& given) {  // (zero where the key gives fewer)
            for (std::size_t j = 0; j < w.width; ++j) {
                const double x = j < given.size() ? given[j] : 0;
                w.put(std::span(&x, 1), where, "weights");
            }
        };
        w.add(s.time, where, [&] {
            if (t.how.weights == method::cubicspline) tangent(spline.weights_in);
            w.put(s.weights, where, "weights");
            if (t.how.weights == method::cubicspline) tangent(spline.weights_out);
        });
    }
}

void gathered_apart::finish() {
    for (stored_track& t : tracks_) tracks_put_.push_back(std::move(t));
    tracks_.clear();
}

}  // namespace keyrot::detail
