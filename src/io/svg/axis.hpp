#pragma once
// An axis's round numbers: ticks at 1, 2 or 5 times a power of ten.
#include <algorithm>
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
    int decimals = 0;           ///< the digits after the point that tell the ticks apart
};

/// An axis over `r` with about `count` intervals (at least one): a range
/// of one value, or none, gets the interval of one unit around it.
axis axis_of(range r, int count);

}  // namespace keyrot::svg
