// SPDX-License-Identifier: MIT
#pragma once
// Invariants every fuzz target checks: a finding aborts.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "ground/text.hpp"
#include "io/common/layout.hpp"
#include "keyrot/track.hpp"

namespace keyrot::fuzz {

inline std::string_view text(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

inline void require(bool ok) {
    if (!ok) std::abort();
}

/// Every key a finite unit quaternion at a finite, strictly increasing time.
inline void check_track(const track& t) {
    require(!t.keys.empty());
    for (std::size_t i = 0; i < t.keys.size(); ++i) {
        const key& k = t.keys[i];
        require(std::isfinite(k.time) && (i == 0 || k.time > t.keys[i - 1].time));
        require(std::fabs(norm(k.rotation) - 1) < 1e-12);
    }
}

/// Every stderr line one printable "keyrot: " line. (NaN and infinity cannot
/// reach the output: the number formatter throws std::logic_error, which
/// escapes the target and is a finding.)
inline void check_output(const std::string& err) {
    std::size_t start = 0;
    while (start < err.size()) {
        const std::size_t end = err.find('\n', start);
        require(end != std::string::npos);
        const std::string_view line(err.data() + start, end - start);
        require(line.rfind("keyrot: ", 0) == 0 && is_valid_utf8(line));
        for (char c : line) require(static_cast<unsigned char>(c) >= 0x20 && c != 0x7f);
        start = end + 1;
    }
}

}  // namespace keyrot::fuzz
