// SPDX-License-Identifier: MIT
#include "io/json/json_object.hpp"

#include "io/common/layout.hpp"
#include "io/json/json.hpp"

namespace keyrot {

std::string json_number(std::optional<double> v) {
    if (!v) return "null";
    std::string out;
    append_number(out, *v, std::nullopt);
    return out;
}

json_object& json_object::text(std::string_view name, std::string_view s) { return raw(name, json_quote(s)); }

json_object& json_object::raw(std::string_view name, std::string_view json) {
    if (!out_.empty()) out_ += ", ";
    out_ += '"';
    out_ += name;
    out_ += "\": ";
    out_ += json;
    return *this;
}

}  // namespace keyrot
