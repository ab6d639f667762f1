// SPDX-License-Identifier: MIT
#pragma once
// An axis's round numbers: ticks at 1, 2 or 5 times a power of ten.
#include <algorithm>
#include <string>
#include <vector>

namespace keyrot::svg {

/// The smallest and largest of some values (none yet: empty()).
struct range {
    double lo = 0, hi = -1;
    bool empty() const { return hi < lo; }
    void add(double v) {
        if (empty()) lo = hi = v;
        else lo = std::min(lo, v), hi = std::max(hi, v);
    }
};

struct axis {
    double lo = 0, hi = 1;      ///< round numbers around the range
    std::vector<double> ticks;  ///< from lo to hi, evenly spaced
    /// Each tick's label: the value less `offset`, with the digits that
    /// tell the ticks apart ("0.25"), or as a multiple of the step's power
    /// of ten where that is beyond 10^6 or 10^-6 ("25e-9", "30e-9").
    std::vector<std::string> labels;
    /// Taken from every label where the ticks are far from zero for their
    /// spacing (times from 1e15 s, a step of 20 s): the first tick in the
    /// range; else 0.
    double offset = 0;
};

/// An axis over `r` with about `count` intervals (at least one): a range
/// of one value, or none, gets the interval of one unit around it.
axis axis_of(range r, int count);

}  // namespace keyrot::svg
