// SPDX-License-Identifier: MIT
#pragma once
// Keys parsed ahead of the caller on threads of their own.
#include <functional>
#include <memory>

#include "io/common/line_keys.hpp"

namespace keyrot {

/// `reader`'s keys, parsed on two threads ahead of the caller once more
/// than a thousand have come and `worth_it()` (asked then, on the caller's
/// thread) says so: a batch of pieces each in turn, with copies of the
/// reader's parser() (none: no threads). The caller must not use the
/// reader's stream.
std::unique_ptr<key_reader> read_ahead(std::unique_ptr<line_key_reader> reader, std::function<bool()> worth_it);

}  // namespace keyrot
