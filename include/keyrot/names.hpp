// SPDX-License-Identifier: MIT
#pragma once
// Enumerations by the names the command line and the files give them: one
// table of {value, name} per enumeration, next to it, and one parse and one
// to_string for all of them.
#include <array>
#include <optional>
#include <string_view>
#include <type_traits>

namespace keyrot {

template <class E>
struct enum_name {
    E value;
    std::string_view name;
};

/// Specialised for each named enumeration: its values and their names, in
/// the order help texts list them. For example
/// `template <> inline constexpr std::array<enum_name<path>, 2> names_of<path> = {{{path::shortest, "shortest"}, ...}};`
template <class E>
inline constexpr std::array<enum_name<E>, 0> names_of{};

/// An enumeration with a table of names.
template <class E>
concept named_enum = std::is_enum_v<E> && (names_of<E>.size() > 0);

/// parse<rep>("axis-angle") = rep::axis_angle; std::nullopt for a name not in names_of<E>.
template <named_enum E>
constexpr std::optional<E> parse(std::string_view name) noexcept {
    for (const auto& [value, n] : names_of<E>)
        if (n == name) return value;
    return std::nullopt;
}

/// to_string(rep::axis_angle) = "axis-angle".
template <named_enum E>
constexpr std::string_view to_string(E value) noexcept {
    for (const auto& [v, name] : names_of<E>)
        if (v == value) return name;
    return "?";
}

}  // namespace keyrot
