// SPDX-License-Identifier: MIT
#pragma once
// A polyline thinned to what its pixels show.
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "io/svg/figure.hpp"

namespace keyrot::svg {

/// The x range a panel shows for what it draws from x0 to x1: that, or
/// for one value a unit around it.
std::pair<double, double> shown_range(double x0, double x1);
/// Where x lands across the plot of a panel that draws from x0 to x1.
double page_x(double x, double x0, double x1);

/// Points in increasing x, each in a column (one a quarter of a pixel
/// wide on the page), reduced as they come to the first, lowest, highest
/// and last of each column, in their order: at most sixteen a pixel, and
/// on the page every point within a quarter of a pixel of the path through them.
class column_extremes {
public:
    /// `column`: the point's, never less than the last point's.
    void add(point p, double column);
    /// The points kept (the last column's among them).
    std::vector<point> finish();

private:
    void flush();
    std::vector<point> kept_;
    std::optional<double> column_;
    point first_, low_, high_, last_;
    std::size_t count_ = 0, low_at_ = 0, high_at_ = 0;  // in the column: points, where low_ and high_ came
};

/// A curve's points, given in the panel's own terms (x from `x0` to `x1`,
/// known before the first point), thinned as they come by the columns the
/// panel will draw them in: what thinned() keeps of the thinned curve is
/// what it keeps of the whole one, and the whole is never held.
class curve_thinner {
public:
    curve_thinner(double x0, double x1) : x0_(x0), x1_(x1) {}
    void add(point p);
    std::vector<point> finish();

private:
    double x0_, x1_;
    column_extremes columns_;
};

/// Of points on the page, in increasing x: column_extremes' points; of
/// those, the ones a straight line past them would miss by more than 0.2
/// pixel. Every point is within 0.45 pixel of the polyline through them,
/// and the highest and lowest are on it.
std::vector<point> thinned(std::span<const point> on_page);

}  // namespace keyrot::svg
