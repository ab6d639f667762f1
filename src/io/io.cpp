#include "io/io.hpp"

#include <fmt/format.h>

#include "ground/text.hpp"

namespace keyrot {

void check_track_name(const std::string& name, const std::string& where) {
    if (has_control_characters(name))
        throw input_error(where, fmt::format("track name '{}' has control characters: expected printable text", excerpt(name)));
}

}  // namespace keyrot
