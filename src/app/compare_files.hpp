// SPDX-License-Identifier: MIT
#pragma once
// compare's reading: each file surveyed in a first pass, then both read
// again in step, their rows matched as they come (keyrot::comparer), so
// that memory does not grow with the files.
#include <functional>
#include <optional>
#include <unordered_set>
#include <vector>

#include "app/app.hpp"
#include "io/document.hpp"
#include "keyrot/compare.hpp"

namespace keyrot::detail {

/// What the first pass learnt of a file: its tracks' surveys, and what
/// compare's hints ask of it.
struct surveyed_file {
    std::string source;
    std::vector<track_survey> tracks;
    /// A JSON document the streaming reader declines, held read whole.
    std::optional<document> whole;
    std::unordered_set<rep> given;         ///< the representations its keys were given in
    std::optional<euler_seq> euler;        ///< its first track's Euler sequence
    bool counted = false;                  ///< some key is timed by its frame number alone
    std::size_t keys = 0;
};

/// Pass 1 over `src`: every key made and checked (each track's times
/// increase), its warnings said. Throws input_error for a bad key.
surveyed_file survey_file(const options& o, const input_source& src, warnings& warn);

/// Pass 2: the key (read with `key_flags`) against an answer (read with
/// `answer_flags`, and each of its keys made otherwise by `answer_as`,
/// where given), both surveyed before; `begin` is told what is known before
/// the first row (missing tracks, frame rates), and each row goes to `row`
/// as it is settled. Warnings were said in pass 1. Throws input_error for a
/// reading under which a key cannot be made.
comparison_summary compare_files(const options& key_flags, const input_source& key_src, const surveyed_file& key,
                                 const options& answer_flags, const input_source& answer_src,
                                 const surveyed_file& answer,
                                 const std::function<void(const comparison_summary&)>& begin,
                                 const comparer::row_sink& row,
                                 const std::function<void(keyrot::key&)>& answer_as = nullptr);

}  // namespace keyrot::detail
