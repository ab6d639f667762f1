#include "io/svg/axis.hpp"

#include <cmath>

namespace keyrot::svg {

axis axis_of(range r, int count) {
    if (r.empty()) r = {0, 1};
    if (!(r.hi > r.lo)) r = {r.lo - 0.5, r.hi + 0.5};
    // The step: the first of 1, 2, 5 (times a power of ten) that gives at
    // most `count` intervals.
    const double raw = (r.hi - r.lo) / std::max(count, 1);
    const double power = std::pow(10.0, std::floor(std::log10(raw)));
    double step = power;
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * power >= raw * (1 - 1e-12)) {
            step = m * power;
            break;
        }
    axis a;
    const double first = std::floor(r.lo / step + 1e-9), last = std::ceil(r.hi / step - 1e-9);
    a.lo = first * step, a.hi = last * step;
    // Each tick computed afresh from its index, never accumulated.
    for (double i = first; i <= last; ++i) a.ticks.push_back(i * step == 0 ? 0 : i * step);
    a.decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
    return a;
}

}  // namespace keyrot::svg
