// SPDX-License-Identifier: MIT
#include "io/common/interface.hpp"

#include <fmt/format.h>

#include "ground/text.hpp"

namespace keyrot {

void check_track_name(const std::string& name, const std::string& where) {
    if (has_control_characters(name))
        throw input_error(where, fmt::format("track name '{}' has control characters: expected printable text", excerpt(name)));
    if (!is_valid_utf8(name))  // (the name goes into every output, and what keyrot writes it reads)
        throw input_error(where, fmt::format("track name '{}' is not UTF-8: expected text", excerpt(name)));
}

std::string distinct_track_name(const std::string& name, std::set<std::string>& taken) {
    std::string distinct = name;
    for (int n = 2; taken.contains(distinct); ++n) distinct = fmt::format("{}.{}", name, n);
    taken.insert(distinct);
    return distinct;
}

}  // namespace keyrot
