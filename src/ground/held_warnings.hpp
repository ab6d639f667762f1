// SPDX-License-Identifier: MIT
#pragma once
// Warnings held back while a way of reading an input is tried.
#include <sstream>

#include "ground/warnings.hpp"
#include "keyrot/error.hpp"

namespace keyrot {

/// Runs attempt(warnings&), a fast way to an input's result that may not
/// take the input, with warnings of its own, held back: printed, and
/// counted as said in `warn`, when it returns true; dropped when it returns
/// false (it declined the input, or guessed wrong) or throws error. The
/// caller then takes the reference way, which words the error in its own
/// order (docs/design.md: "A fast path never words an error").
template <class Attempt>
bool with_held_warnings(warnings& warn, Attempt&& attempt) {
    std::ostringstream held;
    warnings own(held, warn.source());
    try {
        if (!attempt(own)) return false;
    } catch (const error&) {
        return false;
    }
    warn.adopt(own, held.str());
    return true;
}

}  // namespace keyrot
