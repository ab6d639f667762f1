// SPDX-License-Identifier: MIT
#include "io/bvh/track_store.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>

#include "ground/text.hpp"
#include "io/common/spool.hpp"
#include "keyrot/error.hpp"

namespace keyrot {

track_store::track_store(std::size_t width)
    : width_(width), filling_(width * block_) {}

track_store::~track_store() {
    if (file_) std::fclose(file_);
}

void track_store::push(const double* row) {
    std::copy_n(row, width_, filling_.begin() + static_cast<std::ptrdiff_t>(total_ % block_ * width_));
    if (++total_ % block_ == 0) flush();
}

void track_store::flush() {
    if (total_ == block_) file_ = std::tmpfile();  // the first block written: more rows than one holds
    if (!file_) {
        held_.insert(held_.end(), filling_.begin(), filling_.end());
        return;
    }
    if (!write_doubles(file_, filling_.data(), filling_.size(), (total_ / block_ - 1) * filling_.size()))
        throw error(fmt::format("cannot store a BVH output's frames in a temporary file: {}", errno_text()));
}

const double* track_store::load(std::size_t t, std::size_t row) {
    const std::size_t block = row / block_, offset = row % block_ * width_;
    if (block == total_ / block_) return filling_.data() + offset;  // not written yet
    // (at() found no block of track t in its cache.)
    if (cached_.size() < first_.size()) cached_.resize(first_.size(), SIZE_MAX), cache_.resize(first_.size());
    std::vector<double>& cache = cache_[t];
    cache.resize(filling_.size());
    const std::size_t start = block * filling_.size();
    if (!file_) std::copy_n(held_.begin() + static_cast<std::ptrdiff_t>(start), cache.size(), cache.begin());
    else if (!read_doubles(file_, cache.data(), cache.size(), start))
        throw error(fmt::format("cannot read a BVH output's frames back from a temporary file: {}", errno_text()));
    cached_[t] = block;
    return cache.data() + offset;
}

}  // namespace keyrot
