// SPDX-License-Identifier: MIT
#include "io/svg/thin.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <utility>

namespace keyrot::svg {

namespace {

/// Columns a quarter of a pixel wide: a point of one is within a quarter
/// of a pixel of the path through its column's extremes.
constexpr double columns_a_pixel = 4;

double column_at(double x_on_page) { return std::floor(x_on_page * columns_a_pixel); }

/// The distance of `p` from the segment from `a` to `b`.
double distance(point p, point a, point b) {
    const double dx = b.x - a.x, dy = b.y - a.y, length2 = dx * dx + dy * dy;
    const double s = length2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / length2, 0.0, 1.0) : 0;
    return std::hypot(p.x - (a.x + s * dx), p.y - (a.y + s * dy));
}

}  // namespace

std::pair<double, double> shown_range(double x0, double x1) {
    if (!(x1 > x0)) return {x0 - 0.5, x1 + 0.5};
    return {x0, x1};
}

double page_x(double x, double x0, double x1) {
    std::tie(x0, x1) = shown_range(x0, x1);
    return plot_left + (x - x0) / (x1 - x0) * (plot_right - plot_left);
}

void column_extremes::add(point p, double column) {
    if (column_ && *column_ != column) flush();
    if (!column_) {
        column_ = column;
        first_ = low_ = high_ = last_ = p;
        count_ = 1, low_at_ = high_at_ = 0;
        return;
    }
    if (p.y < low_.y) low_ = p, low_at_ = count_;
    if (p.y > high_.y) high_ = p, high_at_ = count_;
    last_ = p;
    ++count_;
}

void column_extremes::flush() {
    std::array<std::pair<std::size_t, point>, 4> picks{
        {{0, first_}, {low_at_, low_}, {high_at_, high_}, {count_ - 1, last_}}};
    std::sort(picks.begin(), picks.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 0; i < picks.size(); ++i)
        if (i == 0 || picks[i].first != picks[i - 1].first) kept_.push_back(picks[i].second);
    column_.reset();
}

std::vector<point> column_extremes::finish() {
    if (column_) flush();
    return std::move(kept_);
}

void curve_thinner::add(point p) { columns_.add(p, column_at(page_x(p.x, x0_, x1_))); }

std::vector<point> curve_thinner::finish() { return columns_.finish(); }

std::vector<point> thinned(std::span<const point> on_page) {
    column_extremes columns;
    for (const point& p : on_page) columns.add(p, column_at(p.x));
    const std::vector<point> extremes = columns.finish();
    if (extremes.size() <= 2) return extremes;
    // Douglas and Peucker's simplification: a point is kept where the line
    // without it would pass farther from it than `tolerance`.
    constexpr double tolerance = 0.2;
    std::vector<bool> keep(extremes.size(), false);
    keep.front() = keep.back() = true;
    std::vector<std::pair<std::size_t, std::size_t>> spans{{0, extremes.size() - 1}};
    while (!spans.empty()) {
        const auto [a, b] = spans.back();
        spans.pop_back();
        std::size_t farthest = a;
        double most = tolerance;
        for (std::size_t i = a + 1; i < b; ++i)
            if (const double d = distance(extremes[i], extremes[a], extremes[b]); d > most) most = d, farthest = i;
        if (farthest == a) continue;
        keep[farthest] = true;
        spans.emplace_back(a, farthest);
        spans.emplace_back(farthest, b);
    }
    std::vector<point> kept;
    for (std::size_t i = 0; i < extremes.size(); ++i)
        if (keep[i]) kept.push_back(extremes[i]);
    return kept;
}

}  // namespace keyrot::svg
