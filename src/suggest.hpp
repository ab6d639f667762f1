// SPDX-License-Identifier: MIT
#pragma once
// "Did you mean": the word a slip of the keyboard was probably meant to be.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace keyrot {

/// Edits from a to b: insertions, deletions, substitutions, and swaps of
/// two neighbouring letters ("--fsp" is one edit from "--fps"); case does
/// not count ("FORMATS" is "formats").
std::size_t edit_distance(std::string_view a, std::string_view b);

/// The name in `names` (not empty) fewest edits away from `word`:
/// nearest("formts", {"formats", "resample"}) = "formats".
std::string nearest(std::string_view word, const std::vector<std::string>& names);

/// The name in `names` that `word`, of `letters` letters (a flag's dashes
/// do not count), was likely meant to be: the one a slip of the keyboard
/// away (one edit for four letters or fewer, two for more), else the longest
/// name of three characters or more that it spells out ("--tolerance":
/// "--tol", "quaternion": "quat"); else none: "--rep" is no "--help".
std::optional<std::string> likely_meant(std::string_view word, const std::vector<std::string>& names,
                                        std::size_t letters);

}  // namespace keyrot
