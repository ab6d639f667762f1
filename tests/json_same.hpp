#pragma once
// json_line against nlohmann-json, the parser it stands in for.
#include <bit>
#include <cstdint>
#include <string_view>

#include <nlohmann/json.hpp>

#include "keyrot/json_line.hpp"

namespace keyrot::test {

/// The same value: type, number to the bit, string bytes, elements in
/// order, members by name. Of a boolean, only the type (no reader asks more).
inline bool same_json(const nlohmann::json& j, json_line::value v) {
    if (std::string_view(j.type_name()) != v.type_name()) return false;
    if (v.is_number()) return std::bit_cast<std::uint64_t>(j.get<double>()) == std::bit_cast<std::uint64_t>(v.number());
    if (v.is_string()) return j.get_ref<const std::string&>() == v.string();
    if (!v.is_array() && !v.is_object()) return true;
    if (j.size() != v.size()) return false;
    for (std::size_t i = 0; i < v.size(); ++i) {
        const json_line::value e = v[i];
        if (v.is_array() ? !same_json(j[i], e) : !j.contains(e.name()) || !same_json(j.at(e.name()), e)) return false;
    }
    return true;
}

}  // namespace keyrot::test
