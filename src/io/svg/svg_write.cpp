// SPDX-License-Identifier: MIT
// The SVG of a figure: panels stacked top to bottom, each with its title,
// legend, axes, grid, curves (thinned to their pixel columns), marks and
// levels. Coordinates to a tenth of a pixel, so the same figure gives the
// same bytes and a curve is placed to well under a pixel.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <set>
#include <tuple>
#include <utility>

#include "io/common/layout.hpp"
#include "io/svg/axis.hpp"
#include "io/svg/figure.hpp"
#include "io/svg/thin.hpp"

namespace keyrot::svg {

namespace {

// A panel from top to bottom: title, legend, plot, tick labels, axis label.
constexpr double title_height = 22, legend_height = 20, tall_plot = 200, short_plot = 110, below_plot = 44, gap = 12;
constexpr double font_size = 12;

struct hex_pair {
    const char* light;  // on the light background
    const char* dark;   // where the viewer prefers dark
};
// Okabe and Ito's palette; the blue, too dark on a dark background, gives way to the sky blue there.
constexpr std::array<hex_pair, 7> palette = {{{"#0072B2", "#56B4E9"},
                                              {"#D55E00", "#E8743B"},
                                              {"#009E73", "#2DBE8E"},
                                              {"#CC79A7", "#DB97BE"},
                                              {"#E69F00", "#F0B53C"},
                                              {"#56B4E9", "#8FD0F5"},
                                              {"#767676", "#A8A8A8"}}};

const hex_pair& of(colour c) { return palette[static_cast<std::size_t>(c)]; }

std::string style() {
    std::string light, dark;
    for (std::size_t i = 0; i < palette.size(); ++i) {
        light += fmt::format(".c{}{{stroke:{}}}", i, palette[i].light);
        dark += fmt::format(".c{}{{stroke:{}}}", i, palette[i].dark);
    }
    return fmt::format(
        "<style type=\"text/css\"><![CDATA[\n"
        ".bg{{fill:#FFFFFF}}text{{fill:#1A1A1A}}.axis{{stroke:#404040}}.grid{{stroke:#E3E3E3}}{}\n"
        "@media (prefers-color-scheme: dark){{.bg{{fill:#1C1C1C}}text{{fill:#E8E8E8}}.axis{{stroke:#B8B8B8}}"
        ".grid{{stroke:#383838}}{}}}\n"
        "]]></style>\n",
        light, dark);
}

/// XML text: the five special characters escaped.
std::string escaped(std::string_view text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            default: out += c;
        }
    }
    return out;
}

/// A coordinate to a tenth of a pixel, without a trailing ".0" or a "-0".
std::string px(double v) {
    std::string out;
    append_number(out, std::round(v * 10) / 10, 1);
    return out;
}

/// The x and y ranges a panel's plot shows, and its place on the page.
struct frame {
    double top = 0, bottom = 0;  // (across, it spans plot_left to plot_right)
    double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
    double x(double v) const { return page_x(v, x0, x1); }
    double y(double v) const { return bottom - (v - y0) / (y1 - y0) * (bottom - top); }
};

/// The smallest and largest of what a panel draws, along x and along y.
std::pair<range, range> extents(const panel& p) {
    range xs, ys;
    for (const curve& c : p.curves)
        for (const point& q : c.points) xs.add(q.x), ys.add(q.y);
    for (const marks& m : p.marked)
        for (const point& q : m.points) xs.add(q.x), ys.add(q.y);
    for (const level& l : p.levels) ys.add(l.y);
    if (p.from_zero) ys.add(0);
    return {xs, ys};
}

void legend_entry(std::string& out, double& x, double y, std::string_view label, const std::string& swatch) {
    out += swatch;
    out += fmt::format("<text x=\"{}\" y=\"{}\">{}</text>\n", px(x + 22), px(y + 4), escaped(label));
    x += 34 + 7 * static_cast<double>(label.size());
}

/// A mark centred on (x, y), on the page.
std::string mark_at(mark_shape shape, double x, double y) {
    if (shape == mark_shape::dot) return fmt::format("M{} {}h0", px(x), px(y));
    return fmt::format("M{} {}l7 7m0-7l-7 7", px(x - 3.5), px(y - 3.5));
}

std::string mark_path(const marks& m, const frame& f) {
    std::set<std::pair<long, long>> drawn;  // the pixels marked already
    std::string d;
    for (const point& q : m.points) {
        const double x = f.x(q.x), y = f.y(q.y);
        if (drawn.emplace(std::lround(x), std::lround(y)).second) d += mark_at(m.shape, x, y);
    }
    return d;
}

std::string mark_style(const marks& m) {
    const std::size_t i = static_cast<std::size_t>(m.hue);
    return m.shape == mark_shape::dot
               ? fmt::format("class=\"c{}\" stroke=\"{}\" stroke-width=\"7\" stroke-linecap=\"round\"", i, of(m.hue).light)
               : fmt::format("class=\"c{}\" stroke=\"{}\" stroke-width=\"2\"", i, of(m.hue).light);
}

std::string curve_style(colour hue) {
    return fmt::format("class=\"c{}\" stroke=\"{}\" stroke-width=\"1.75\" stroke-linejoin=\"round\"",
                       static_cast<std::size_t>(hue), of(hue).light);
}

std::string level_style() {
    return fmt::format("class=\"c{}\" stroke=\"{}\" stroke-width=\"1.25\" stroke-dasharray=\"6 4\"",
                       static_cast<std::size_t>(colour::grey), of(colour::grey).light);
}

/// How many things a panel's legend names (those with a label).
std::size_t named(const panel& p) {
    const auto labelled = [](const auto& list) {
        return static_cast<std::size_t>(std::count_if(list.begin(), list.end(), [](const auto& e) { return !e.label.empty(); }));
    };
    return labelled(p.curves) + labelled(p.marked) + labelled(p.levels);
}

/// The legend, where there is more than one thing to tell apart.
void draw_legend(std::string& out, const panel& p, double y) {
    if (named(p) < 2) return;
    double x = plot_left;
    for (const curve& c : p.curves)
        if (!c.label.empty())
            legend_entry(out, x, y, c.label,
                         fmt::format("<path d=\"M{} {}h16\" fill=\"none\" {}/>\n", px(x), px(y), curve_style(c.hue)));
    for (const marks& m : p.marked)
        if (!m.label.empty())
            legend_entry(out, x, y, m.label,
                     fmt::format("<path d=\"{}\" fill=\"none\" {}/>\n", mark_at(m.shape, x + 8, y), mark_style(m)));
    for (const level& l : p.levels)
        if (!l.label.empty())
            legend_entry(out, x, y, l.label, fmt::format("<path d=\"M{} {}h16\" {}/>\n", px(x), px(y), level_style()));
}

/// An axis's name, with what its labels are less of ("time (s) − 1000000000000000").
std::string axis_name(const std::string& name, const axis& a) {
    if (a.offset == 0) return escaped(name);
    std::string offset;
    append_number(offset, a.offset, std::nullopt);
    return escaped(name) + " \u2212 " + offset;
}

/// The axes, their grid and labels; of the x axis's ticks, those inside the plot.
void draw_axes(std::string& out, const panel& p, const frame& f, const axis& x_axis, const axis& y_axis) {
    std::string grid, labels;
    for (std::size_t i = 0; i < y_axis.ticks.size(); ++i) {
        const double y = f.y(y_axis.ticks[i]);
        grid += fmt::format("M{} {}H{}", px(plot_left), px(y), px(plot_right));
        labels += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>\n", px(plot_left - 6), px(y + 4),
                              y_axis.labels[i]);
    }
    const double slack = 1e-9 * (f.x1 - f.x0);
    for (std::size_t i = 0; i < x_axis.ticks.size(); ++i) {
        const double v = x_axis.ticks[i];
        if (v < f.x0 - slack || v > f.x1 + slack) continue;
        grid += fmt::format("M{} {}V{}", px(f.x(v)), px(f.top), px(f.bottom));
        labels += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", px(f.x(v)),
                              px(f.bottom + 16), x_axis.labels[i]);
    }
    out += fmt::format("<path class=\"grid\" d=\"{}\" stroke=\"#E3E3E3\" stroke-width=\"1\"/>\n", grid);
    out += fmt::format("<path class=\"axis\" d=\"M{} {}V{}H{}\" fill=\"none\" stroke=\"#404040\" stroke-width=\"1\"/>\n",
                       px(plot_left), px(f.top), px(f.bottom), px(plot_right));
    out += labels;
    out += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", px((plot_left + plot_right) / 2),
                       px(f.bottom + 36), axis_name(p.x_label, x_axis));
    const double mid = (f.top + f.bottom) / 2;
    out += fmt::format("<text x=\"{0}\" y=\"{1}\" text-anchor=\"middle\" transform=\"rotate(-90 {0} {1})\">{2}</text>\n",
                       px(16), px(mid), axis_name(p.y_label, y_axis));
}

/// Draws panel `p` from `top`, a group of its own; returns where the next one begins.
double draw_panel(std::string& out, const panel& p, double top) {
    out += "<g class=\"panel\">\n";
    out += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"14\" font-weight=\"bold\">{}</text>\n", px(plot_left),
                       px(top + 15), escaped(p.title));
    const bool legend = named(p) >= 2;
    draw_legend(out, p, top + title_height + 8);
    frame f;
    f.top = top + title_height + (legend ? legend_height : 0) + 6;
    f.bottom = f.top + (p.short_plot ? short_plot : tall_plot);
    auto [xs, ys] = extents(p);
    if (p.from_zero && !(ys.hi > 0)) ys.add(1);  // nothing but zeros: zero at the foot of a unit axis
    // The y axis spans its round ticks; the x axis spans the data (time
    // from the first key to the last), with the round ticks inside it.
    const axis y_axis = axis_of(ys, p.short_plot ? 3 : 5);
    f.y0 = y_axis.lo, f.y1 = y_axis.hi;
    std::tie(f.x0, f.x1) = xs.empty() ? std::pair(0.0, 1.0) : shown_range(xs.lo, xs.hi);
    draw_axes(out, p, f, axis_of(range{f.x0, f.x1}, 8), y_axis);
    for (const level& l : p.levels)
        out += fmt::format("<path d=\"M{} {}H{}\" {}/>\n", px(plot_left), px(f.y(l.y)), px(plot_right), level_style());
    for (const curve& c : p.curves) {
        std::vector<point> on_page;
        on_page.reserve(c.points.size());
        for (const point& q : c.points) on_page.push_back({f.x(q.x), f.y(q.y)});
        std::string d;
        for (const point& q : thinned(on_page)) d += fmt::format("{}{} {}", d.empty() ? "M" : " ", px(q.x), px(q.y));
        if (!d.empty()) out += fmt::format("<path d=\"{}\" fill=\"none\" {}/>\n", d, curve_style(c.hue));
    }
    for (const marks& m : p.marked) {
        const std::string d = mark_path(m, f);
        if (!d.empty()) out += fmt::format("<path d=\"{}\" fill=\"none\" {}/>\n", d, mark_style(m));
    }
    out += "</g>\n";
    return f.bottom + below_plot + gap;
}

}  // namespace

std::string to_svg(const figure& fig) {
    std::string body;
    double y = gap;
    for (const panel& p : fig.panels) y = draw_panel(body, p, y);
    const std::string height = px(y);
    return fmt::format(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"{0}\" height=\"{1}\" "
        "viewBox=\"0 0 {0} {1}\" font-family=\"sans-serif\" font-size=\"{2}\">\n"
        "{3}<rect class=\"bg\" width=\"{0}\" height=\"{1}\" fill=\"#FFFFFF\"/>\n{4}</svg>\n",
        px(width), height, px(font_size), style(), body);
}

}  // namespace keyrot::svg
