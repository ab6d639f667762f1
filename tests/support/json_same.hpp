// SPDX-License-Identifier: MIT
#pragma once
// flat_json against nlohmann-json, the parser it stands in for.
#include <bit>
#include <cstdint>
#include <string_view>

#include <nlohmann/json.hpp>

#include "io/json/flat_json.hpp"

namespace keyrot::test {

/// The same value: type, number to the bit, string bytes, elements and
/// members in the same order. Of a boolean, only the type (no reader asks
/// more).
inline bool same_json(const nlohmann::ordered_json& j, flat_json::value v) {
    if (std::string_view(j.type_name()) != v.type_name()) return false;
    if (v.is_number()) return std::bit_cast<std::uint64_t>(j.get<double>()) == std::bit_cast<std::uint64_t>(v.number());
    if (v.is_string()) return j.get_ref<const std::string&>() == v.string();
    if (!v.is_array() && !v.is_object()) return true;
    if (j.size() != v.size()) return false;
    bool same = true;
    std::size_t i = 0;
    if (v.is_array()) v.elements([&](flat_json::value e) { same = same && same_json(j[i++], e); });
    auto member = j.begin();
    if (v.is_object()) v.members([&](std::string_view name, flat_json::value e) {
        same = same && member.key() == name && same_json(member.value(), e);
        ++member;
    });
    return same;
}

}  // namespace keyrot::test
