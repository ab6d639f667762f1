// SPDX-License-Identifier: MIT
#pragma once
// The command line: CLI11 definitions that fill an options struct.
#include <iosfwd>
#include <optional>

#include "app/app.hpp"

namespace keyrot {

/// keyrot's version, from CMake's project().
extern const char* const version;

/// Parses argv. Returns std::nullopt after printing --help or --version to
/// `out` (exit status 0). Throws usage_error for a bad command line.
std::optional<options> parse_command_line(int argc, const char* const* argv, std::ostream& out);

}  // namespace keyrot
