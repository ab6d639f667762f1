// SPDX-License-Identifier: MIT
#pragma once
// A BVH take's values, a column per channel, kept in a temporary file so
// that reading a long take does not grow with it.
#include <cstddef>
#include <cstdio>
#include <vector>

namespace keyrot {

/// A column of numbers per channel, frame after frame, kept in a temporary
/// file (unlinked at once) in blocks of a few thousand frames, so that
/// memory does not grow with the take: a block of every channel is
/// gathered, then written; a value is read back with its channel's block.
/// The file is made when the first block is written; where none can be
/// made, the blocks stay in memory.
class column_store {
public:
    /// `frames`: as many as the take states (the reader refuses more).
    column_store(std::size_t width, std::size_t frames);
    column_store(const column_store&) = delete;
    column_store& operator=(const column_store&) = delete;
    ~column_store();

    /// Appends a frame's values (width of them).
    void push(const double* row) {
        const std::size_t at = frames_ % block_;
        for (std::size_t c = 0; c < width_; ++c) filling_[c * block_ + at] = row[c];
        if (++frames_ % block_ == 0) flush();
    }

    /// The value of channel `c` at `frame` (read in order within a channel).
    double at(std::size_t c, std::size_t frame) {
        const std::size_t block = frame / block_, offset = frame % block_;
        if (block == frames_ / block_) return filling_[c * block_ + offset];  // not written yet
        if (cached_[c] != block) load(c, block);
        return cache_[c * block_ + offset];
    }

private:
    void flush();
    void load(std::size_t c, std::size_t block);

    std::size_t width_, block_;
    std::size_t frames_ = 0;
    std::vector<double> filling_;       // the block being gathered, channel after channel
    std::vector<std::size_t> cached_;   // each channel's block in cache_
    std::vector<double> cache_;
    std::FILE* file_ = nullptr;
    std::vector<double> held_;  // the written blocks, without a temporary file
};

}  // namespace keyrot
