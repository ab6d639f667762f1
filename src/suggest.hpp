#pragma once
// "Did you mean": the word a slip of the keyboard was probably meant to be.
#include <cstddef>
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

}  // namespace keyrot
