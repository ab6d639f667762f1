// SPDX-License-Identifier: MIT
#pragma once
// The interpolation methods and paths by name: what --method and --path
// choose, and what a glTF sampler states.
#include <array>

#include "keyrot/names.hpp"

namespace keyrot {

/// How a track is interpolated between keys. `cubic` is the rotation
/// spline of keyrot/rotation_spline.hpp; `cubicspline` is glTF's
/// CUBICSPLINE, which needs the tangents only a glTF file gives its keys.
enum class method { slerp, nlerp, squad, step, euler, cubic, cubicspline };
template <>
inline constexpr std::array<enum_name<method>, 7> names_of<method> = {{{method::slerp, "slerp"},
                                                                   {method::nlerp, "nlerp"},
                                                                   {method::squad, "squad"},
                                                                   {method::step, "step"},
                                                                   {method::euler, "euler"},
                                                                   {method::cubic, "cubic"},
                                                                   {method::cubicspline, "cubicspline"}}};

enum class path { shortest, direct };
template <>
inline constexpr std::array<enum_name<path>, 2> names_of<path> = {{{path::shortest, "shortest"}, {path::direct, "direct"}}};

}  // namespace keyrot
