// SPDX-License-Identifier: MIT
#include "keyrot/track.hpp"

#include <fmt/format.h>

namespace keyrot {

void not_next(const key& previous, const key& next, const std::string& source) {
    if (!(next.time > previous.time))
        throw input_error(where(source, next.at), fmt::format("time {} s is not after the previous key's {} s: "
                                                              "expected strictly increasing times",
                                                              next.time, previous.time));
    throw input_error(where(source, next.at),
                      fmt::format("{} morph weights after a key with {}: expected as many on every key of a track",
                                  next.weights.size(), previous.weights.size()));
}

std::string where(const std::string& source, const location& at) {
    return at.path.empty() ? where(source, at.line) : where(source, at.path);
}

std::string where(std::string_view source, std::size_t line) {
    return line ? fmt::format("{}:{}", source, line) : std::string(source);
}

std::string where(std::string_view source, std::string_view path) { return fmt::format("{}: {}", source, path); }

}  // namespace keyrot
