// SPDX-License-Identifier: MIT
#include "app/usage_error.hpp"

namespace keyrot {

usage_error in_flags(const option_error& e) {
    if (e.which == option::euler_sequence)
        return usage_error("--method euler needs an Euler sequence: expected --euler SEQ");
    if (e.which == option::method) return usage_error(std::string("--method: ") + e.what());
    return usage_error(e.what());
}

}  // namespace keyrot
