// SPDX-License-Identifier: MIT
#include "io/common/raw_key.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "keyrot/tolerances.hpp"

namespace keyrot {
namespace {

quat unit_quaternion(const raw_key& k, const key_settings& s, warnings& warn, bool& renormalised) {
    const auto& v = k.values;
    const quat q{v[0], v[1], v[2], v[3]};
    const double n = norm(q);
    if (n == 0) throw input_error(where(warn.source(), k.at), "quaternion is zero: expected a non-zero quaternion");
    if (std::fabs(n - 1) > tol::unit_norm) {
        const auto what = fmt::format("quaternion norm {} differs from 1 by more than {}", n, tol::unit_norm);
        if (s.strict) throw input_error(where(warn.source(), k.at), what + " (--strict)");
        warn.once("norm", fmt::format("{} ({}); such keys are normalised", what, where(warn.source(), k.at)));
        renormalised = true;
    }
    return normalized(q, n);
}

quat axis_angle_rotation(const raw_key& k, angle_unit unit, const std::string& source) {
    const auto& v = k.values;
    const vec3 axis{v[0], v[1], v[2]};
    if (norm(axis) == 0) {
        if (v[3] != 0) throw input_error(where(source, k.at), "axis is zero: expected a non-zero axis for a non-zero angle");
        return {};
    }
    return from_axis_angle(axis, v[3], unit);
}

quat matrix_rotation(const raw_key& k, const std::string& source) {
    const auto& v = k.values;
    const std::size_t cols = k.kind == rep::matrix4 ? 4 : 3;
    mat3 m;
    for (std::size_t r = 0; r < 3; ++r)
        for (std::size_t c = 0; c < 3; ++c) m.m[r][c] = v[r * cols + c];
    if (k.kind == rep::matrix4) {
        const double bottom[4] = {v[12], v[13], v[14], v[15]};
        if (bottom[0] != 0 || bottom[1] != 0 || bottom[2] != 0 || bottom[3] != 1)
            throw input_error(where(source, k.at), fmt::format("4x4 matrix bottom row is [{}, {}, {}, {}]: expected [0, 0, 0, 1]",
                                                   bottom[0], bottom[1], bottom[2], bottom[3]));
    }
    double worst = 0;  // max |R R^T - I|
    for (std::size_t r = 0; r < 3; ++r)
        for (std::size_t c = 0; c < 3; ++c) {
            double e = r == c ? -1.0 : 0.0;
            for (std::size_t i = 0; i < 3; ++i) e += m.m[r][i] * m.m[c][i];
            worst = std::fmax(worst, std::fabs(e));
        }
    const auto& a = m.m;
    const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                       a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                       a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    if (worst > tol::orthonormal)
        throw input_error(where(source, k.at), fmt::format("matrix is not a rotation: |R Rt - I| = {:.3g}, expected at most {}",
                                               worst, tol::orthonormal));
    if (det < 0)
        throw input_error(where(source, k.at), fmt::format("matrix is not a rotation: determinant {:.6g}, expected +1 "
                                               "(a reflection)", det));
    return from_matrix(m);
}

}  // namespace

key make_key(const raw_key& k, const key_settings& s, warnings& warn) {
    const std::string& source = warn.source();
    // A unit the key's names state describes the file, over the flags'.
    const angle_unit unit = k.angles.value_or(s.angles);
    if (unit != s.angles && s.angles_given)
        warn.once("conflict angles",
                  fmt::format("the file's angles in {}, as its names say, are used, not --radians", to_string(unit)));
    key out;
    out.at.line = k.at.line;
    if (!k.at.path.empty()) out.at.path = k.at.path;  // (a line's key has none: most keys copy no text)
    out.given_as = k.kind;
    out.translation = k.translation;
    out.scale = k.scale;
    if (!k.weights.empty()) out.weights = k.weights;
    const auto radians = [&](const std::optional<vec3>& v) -> std::optional<vec3> {
        if (!v) return std::nullopt;
        return vec3{to_radians(v->x, unit), to_radians(v->y, unit), to_radians(v->z, unit)};
    };
    if (k.rates.any())
        out.rates = std::make_shared<const frame_rates>(
            frame_rates{radians(k.rates.velocity), radians(k.rates.acceleration)});
    if (k.spline) out.spline = std::make_shared<const full_spline_key>(*k.spline);
    // A row with both is a frame of keyrot's own output, at whatever rate it
    // was made, or a table's row: its time times it, its frame is kept as a
    // label (compare matches by it); but a --key-fps typed times the frame.
    out.frame = k.frame;
    out.has_time = k.time.has_value();
    out.time = k.time && !(k.frame && s.key_fps_given) ? *k.time : *k.frame / s.frame_rate();
    if (k.time && std::fabs(out.time - *k.time) > tol::match_time)
        warn.once("key rate", fmt::format("frame {} is {} s at --key-fps {}, where the file says {} s: frames are "
                                          "timed at --key-fps ({})",
                                          *k.frame, out.time, s.frame_rate(), *k.time, where(source, k.at)));
    if (!k.unknown.empty()) unknown_field(k.unknown, where(source, k.at), s, warn);
    const auto& v = k.values;
    switch (k.kind) {
        case rep::quat: out.rotation = unit_quaternion(k, s, warn, out.renormalised); break;
        case rep::axis_angle: out.rotation = axis_angle_rotation(k, unit, source); break;
        case rep::rotvec:
            out.rotation = from_rotvec({v[0], v[1], v[2]}, unit);
            break;
        case rep::euler: {
            if (!s.euler)
                throw input_error(where(source, k.at), "Euler angles need a sequence: expected --euler SEQ or an \"euler\" field");
            out.rotation = from_euler({v[0], v[1], v[2]}, *s.euler, unit);
            break;
        }
        case rep::matrix:
        case rep::matrix4:
            out.rotation = matrix_rotation(k, source);
            if (k.kind == rep::matrix4) {
                if (k.translation)
                    throw input_error(where(source, k.at), "4x4 matrix and a translation: expected one translation per key");
                out.translation = vec3{v[3], v[7], v[11]};
            }
            break;
    }
    if (k.kind != rep::matrix && k.kind != rep::matrix4) out.given = given_rotation{{v[0], v[1], v[2], v[3]}, unit};
    if (!std::isfinite(out.time))
        throw input_error(where(source, k.at), fmt::format("time {} is out of range: expected a finite time", out.time));
    if (unit == angle_unit::radians && (k.kind == rep::axis_angle || k.kind == rep::rotvec)) {
        // An angle of more than two turns is no one's radians: degrees, read as radians.
        const double angle = k.kind == rep::axis_angle ? std::fabs(v[3]) : norm(vec3{v[0], v[1], v[2]});
        if (angle > 4 * std::numbers::pi)
            warn.once("radians", fmt::format("an angle of {:.6g} read as radians is {:.3g} turns ({}): if the file "
                                             "is in degrees, read it as degrees (without --radians)",
                                             angle, angle / (2 * std::numbers::pi), where(source, k.at)));
    }
    return out;
}

void unknown_field(std::string_view name, const std::string& where, const key_settings& settings, warnings& warn) {
    const std::string what = fmt::format("unknown field '{}'", excerpt(name));
    if (settings.strict) throw input_error(where, what + ": expected only fields keyrot reads (--strict)");
    warn.once("field", fmt::format("ignoring {} ({})", what, where));
}

track_builder::track_builder(std::string name, location at, key_settings settings)
    : at_(std::move(at)),
      settings_(std::move(settings)),
      track_{std::move(name), settings_.euler, {}, settings_.key_fps, settings_.interpolation} {}

void track_builder::add(const raw_key& raw, warnings& warn) {
    key k = make_key(raw, settings_, warn);
    if (!track_.keys.empty()) check_next(track_.keys.back(), k, warn.source());
    track_.keys.push_back(std::move(k));
}

track track_builder::finish(warnings& warn) && {
    if (track_.keys.empty())
        throw input_error(where(warn.source(), at_),
                          track_.name.empty() ? std::string("no keys: expected at least one key")
                                              : fmt::format("track '{}' has no keys: expected at least one key", track_.name));
    return std::move(track_);
}

}  // namespace keyrot
