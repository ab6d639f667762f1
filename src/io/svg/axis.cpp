// SPDX-License-Identifier: MIT
#include "io/svg/axis.hpp"

#include <fmt/format.h>

#include <cmath>
#include <algorithm>
#include <cstdlib>

#include "io/common/layout.hpp"

namespace keyrot::svg {

namespace {

/// The label of `index` steps of `multiple` times 10^`exponent`.
std::string label_of(long long index, int multiple, int exponent) {
    long long digits = index * multiple;
    if (exponent >= -6 && exponent <= 6) {
        std::string out;
        append_number(out, static_cast<double>(digits) * std::pow(10.0, exponent), std::max(0, -exponent));
        return out;
    }
    if (digits == 0) return "0";
    return fmt::format("{}e{}", digits, exponent);  // every label of the axis with the same exponent
}

}  // namespace

axis axis_of(range r, int count) {
    if (r.empty()) r = {0, 1};
    if (!(r.hi > r.lo)) r = {r.lo - 0.5, r.hi + 0.5};
    // A range narrower than the rounding of its values (a constant curve's
    // noise) is widened to that, so that a tick's index stays an integer.
    const double rounding = std::max(std::abs(r.lo), std::abs(r.hi)) * 1e-15;
    if (r.hi - r.lo < rounding) r = {r.lo - rounding, r.hi + rounding};
    // The step: the first of 1, 2, 5 (times a power of ten) that gives at
    // most `count` intervals.
    const double raw = (r.hi - r.lo) / std::max(count, 1);
    int exponent = static_cast<int>(std::floor(std::log10(raw)));
    int multiple = 10;
    for (int m : {1, 2, 5})
        if (m * std::pow(10.0, exponent) >= raw * (1 - 1e-12)) {
            multiple = m;
            break;
        }
    if (multiple == 10) multiple = 1, ++exponent;
    const double step = multiple * std::pow(10.0, exponent);
    axis a;
    const auto first = static_cast<long long>(std::floor(r.lo / step + 1e-9));
    const auto last = static_cast<long long>(std::ceil(r.hi / step - 1e-9));
    a.lo = static_cast<double>(first) * step, a.hi = static_cast<double>(last) * step;
    // Far from zero for its step (more than six significant digits a label):
    // labels from the first tick in the range.
    const bool offset = std::max(std::llabs(first), std::llabs(last)) >= 1000000;
    const long long base = offset ? static_cast<long long>(std::ceil(r.lo / step - 1e-9)) : 0;
    a.offset = static_cast<double>(base) * step;
    // Each tick computed afresh from its index, never accumulated.
    for (long long i = first; i <= last; ++i) {
        a.ticks.push_back(i == 0 ? 0 : static_cast<double>(i) * step);
        a.labels.push_back(label_of(i - base, multiple, exponent));
    }
    return a;
}

}  // namespace keyrot::svg
