// SPDX-License-Identifier: MIT
#pragma once
// Removing a replaced output without waiting for its blocks to be freed.

#include <sys/types.h>

#include <string>

namespace keyrot {

/// Removes the file at `path`, `size` bytes long. A large file's space is
/// freed by a small process of its own, after keyrot may have ended: on a
/// filesystem that discards freed blocks at once (ext4 mounted with
/// `discard`, as on many cloud disks), freeing them waits for the disk.
void remove_replaced(const std::string& path, off_t size) noexcept;

}  // namespace keyrot
