// SPDX-License-Identifier: MIT
#pragma once
// `keyrot help formats`: what a file needs, per representation.
#include <string>

namespace keyrot {

/// The CSV columns and JSON fields of each representation, and how a
/// document is laid out, as `keyrot help formats` prints them.
std::string formats_help();

}  // namespace keyrot
