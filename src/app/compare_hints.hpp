// SPDX-License-Identifier: MIT
#pragma once
// Why an answer fails, where keyrot can tell: the likely cause compare
// names beside the grade (never changing it).
#include <string>
#include <utility>
#include <vector>

#include "app/compare_files.hpp"

namespace keyrot::detail {

/// The answer's tracks that are the key's but for the case of their names:
/// (the key's name, the answer's), of the tracks missing from the answer
/// and only in it.
std::vector<std::pair<std::string, std::string>> tracks_named_in_another_case(const comparison_summary& c);

/// Where an answer (`src`, surveyed as `answer`) fails against the key
/// (`key_src`, `key`) as `c` says, its likely cause; "" where none is
/// found. Track names that differ only in case; rows both missing and extra
/// where frame numbers carry no times (the rate each file counts at); and,
/// for answers of up to 100,000 keys, another reading under which every
/// row passes: degrees read as radians or the reverse, the other
/// quaternion order (of a JSON array, or of a CSV's columns under their
/// header), another Euler sequence.
std::string likely_cause(const options& o, const input_source& key_src, const surveyed_file& key,
                         const input_source& src, const surveyed_file& answer, const comparison_summary& c);

}  // namespace keyrot::detail
