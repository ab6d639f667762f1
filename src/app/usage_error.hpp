// SPDX-License-Identifier: MIT
#pragma once
// The command line's errors, and the core's option errors said in flags.
#include <string>

#include "keyrot/error.hpp"

namespace keyrot {

/// A bad command line: it stops the whole run, where bad input stops one file.
struct usage_error : option_error {
    using option_error::option_error;
};

/// `e` in the words of the command line: the core's "method euler needs an
/// Euler sequence" is "--method euler needs an Euler sequence: expected
/// --euler SEQ".
usage_error in_flags(const option_error& e);

}  // namespace keyrot
