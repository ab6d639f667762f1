// SPDX-License-Identifier: MIT
#pragma once
// A stream of keys made into rows as they arrive, track by track; and the
// tracks of an input read apart made into rows on threads of their own.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/row_sources.hpp"

namespace keyrot::detail {

/// The keys read and the rows made so far (whether parsing ahead pays).
struct row_counts {
    std::size_t keys = 0, rows = 0;
};

/// `reader`'s keys into `rows` by `source`, each track's rows made as its
/// keys arrive with the values of their own `own` gives them
/// (`source_name` names the input). With `known` (pass 1's
/// facts) the keys are known to be good; without (one pass), each track
/// is taken to carry the channels its first key carries, and the keys are
/// checked as pass 1 checks them. Returns the facts seen, or nothing when a
/// track comes back after another one began, or the reader declines the
/// document.
std::optional<document_facts> stream_keys(key_reader& reader, row_source& source, table_output& rows, own_values own,
                                          row_counts& counts, const document_facts* known,
                                          const std::string& source_name, warnings& warn);

/// As stream_keys without `known`, for an input whose tracks `readers()`
/// reads apart (a reader each, in order): each track's rows made by a
/// row source of its own, on whichever thread is free, into an output of
/// its own, which is put into `rows` in order once every track is made.
/// Nothing is put, and nothing returned, where `source` or `rows` cannot
/// take tracks apart (then `readers` is not called), it gives fewer than
/// two readers, the system has one core, or a track warns: the caller
/// then streams the input, which says the warnings in order.
/// What a track throws is thrown, the first track's first.
std::optional<document_facts> rows_apart(const std::function<std::vector<std::unique_ptr<key_reader>>()>& readers,
                                         const row_source& source, table_output& rows, const own_values& own,
                                         const std::string& source_name);

}  // namespace keyrot::detail
