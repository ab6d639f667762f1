// SPDX-License-Identifier: MIT
#include "io/bvh/column_store.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>

#include "ground/text.hpp"
#include "io/common/spool.hpp"
#include "keyrot/error.hpp"

namespace keyrot {

namespace {

/// Frames a block: 2 MiB of values, within [64, 4096] frames. A take
/// shorter than that gets a block one frame longer than itself, which never
/// fills: nothing is written, no file made, no more than its values zeroed.
std::size_t block_frames(std::size_t width, std::size_t frames) {
    const std::size_t block = std::clamp<std::size_t>((std::size_t{1} << 18) / width, 64, 4096);
    return frames < block ? frames + 1 : block;
}

}  // namespace

column_store::column_store(std::size_t width, std::size_t frames)
    : width_(width),
      block_(block_frames(width, frames)),
      filling_(width * block_),
      cached_(width, SIZE_MAX),
      cache_(width * block_) {}

column_store::~column_store() {
    if (file_) std::fclose(file_);
}

void column_store::flush() {
    if (frames_ == block_) file_ = std::tmpfile();  // the first block written: a take longer than one
    if (!file_) {
        held_.insert(held_.end(), filling_.begin(), filling_.end());
        return;
    }
    const std::size_t start = (frames_ / block_ - 1) * width_ * block_;
    if (!write_doubles(file_, filling_.data(), filling_.size(), start))
        throw error(fmt::format("cannot store a BVH file's frames in a temporary file: {}", errno_text()));
}

void column_store::load(std::size_t c, std::size_t block) {
    double* into = cache_.data() + c * block_;
    const std::size_t start = (block * width_ + c) * block_;
    if (!file_) std::copy_n(held_.begin() + static_cast<std::ptrdiff_t>(start), block_, into);
    else if (!read_doubles(file_, into, block_, start))
        throw error(fmt::format("cannot read a BVH file's frames back from a temporary file: {}", errno_text()));
    cached_[c] = block;
}

}  // namespace keyrot
