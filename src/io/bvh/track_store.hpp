// SPDX-License-Identifier: MIT
#pragma once
// The rows of a BVH output, which come a joint at a time and go out a frame
// (every joint's row) at a time, kept in a temporary file so that writing
// a long take does not grow with it: column_store's counterpart.
#include <cstddef>
#include <cstdio>
#include <vector>

namespace keyrot {

/// Rows of `width` numbers, appended track after track, read back frame
/// after frame across the tracks. Kept in a temporary file (unlinked at
/// once) in blocks of rows; a track's block is read back when its rows are
/// reached, so memory is a block per track. The file is made when the
/// first block is written; where none can be made, the blocks stay in memory.
class track_store {
public:
    explicit track_store(std::size_t width);
    track_store(const track_store&) = delete;
    track_store& operator=(const track_store&) = delete;
    ~track_store();

    /// The rows pushed from now on are the next track's.
    void begin_track() { first_.push_back(total_); }
    /// Appends a row (width numbers) to the current track.
    void push(const double* row);
    std::size_t tracks() const noexcept { return first_.size(); }
    std::size_t rows(std::size_t track) const noexcept {
        return (track + 1 < first_.size() ? first_[track + 1] : total_) - first_[track];
    }
    /// Row `i` of track `t`, valid until `t`'s next row is asked for (a
    /// track's rows are read in order).
    const double* at(std::size_t t, std::size_t i) {
        const std::size_t row = first_[t] + i, block = row / block_;
        if (t < cached_.size() && cached_[t] == block) return cache_[t].data() + row % block_ * width_;
        return load(t, row);
    }

private:
    static constexpr std::size_t block_ = 1024;  // rows per block
    void flush();
    const double* load(std::size_t t, std::size_t row);

    std::size_t width_;                        // numbers per row
    std::size_t total_ = 0;                    // rows pushed
    std::vector<std::size_t> first_;           // each track's first row
    std::vector<double> filling_;              // the block being gathered
    std::vector<std::size_t> cached_;          // per track, its block in cache_
    std::vector<std::vector<double>> cache_;  // per track, a block
    std::FILE* file_ = nullptr;
    std::vector<double> held_;  // the written blocks, without a temporary file
};

}  // namespace keyrot
