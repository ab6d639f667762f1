// SPDX-License-Identifier: MIT
#pragma once
// Pictures: a figure of panels stacked one above the other, each a plot of
// curves, marks and levels against one x axis, written as a standalone SVG
// 1.1 document. The module knows nothing of rotations: the commands turn
// tracks into curves (src/app/plots.hpp), and this draws them.
#include <cstddef>
#include <string>
#include <vector>

namespace keyrot::svg {

struct point {
    double x = 0, y = 0;
};

/// One of the figure's colours (the Okabe-Ito palette, told apart by
/// colour-blind readers, each with a lighter variant on a dark background).
enum class colour : unsigned char { blue, vermillion, green, purple, orange, sky, grey };

/// A polyline through points in increasing x. Drawn thinned to what its
/// pixel columns show (the first, lowest, highest and last point of each),
/// so that a curve of a million points costs the bytes of a few thousand
/// and keeps every extreme.
struct curve {
    std::string label;  ///< in the legend
    colour hue = colour::blue;
    std::vector<point> points;
};

enum class mark_shape : unsigned char { dot, cross };

/// Points marked one by one (keys, failing rows); marks that would land on
/// the same pixel are drawn once.
struct marks {
    std::string label;
    colour hue = colour::blue;
    mark_shape shape = mark_shape::dot;
    std::vector<point> points;
};

/// A dashed horizontal line across the plot: a tolerance.
struct level {
    std::string label;
    double y = 0;
};

struct panel {
    std::string title;
    std::string x_label, y_label;  ///< with their units: "time (s)", "angle (deg)"
    std::vector<curve> curves;
    std::vector<marks> marked;
    std::vector<level> levels;
    bool from_zero = false;  ///< the y axis reaches 0 (a speed, a difference)
    bool short_plot = false; ///< a lower plot, under the one it belongs to
};

struct figure {
    std::vector<panel> panels;
};

/// The figure's size and plot area, in pixels (user units of the viewBox).
inline constexpr double width = 800, plot_left = 72, plot_right = 780;

/// The figure as an SVG 1.1 document with a viewBox: valid XML, text in a
/// generic font family (sans-serif), a background of its own with the
/// colours of a dark one where the viewer prefers dark, and the same bytes
/// for the same figure. Text is escaped; it must be UTF-8.
std::string to_svg(const figure& f);

}  // namespace keyrot::svg
