// SPDX-License-Identifier: MIT
// The picture writer: round axis ticks, polylines thinned within half a
// pixel with every extreme kept, and the SVG text itself.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "io/svg/axis.hpp"
#include "io/svg/figure.hpp"
#include "io/svg/thin.hpp"

using namespace keyrot::svg;

namespace {

axis over(double lo, double hi, int count) {
    range r;
    r.add(lo), r.add(hi);
    return axis_of(r, count);
}

/// The distance from `p` to the polyline `line` (points in increasing x).
double off_line(point p, const std::vector<point>& line) {
    double best = INFINITY;
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
        const point a = line[i], b = line[i + 1];
        if (p.x < a.x - 1 || p.x > b.x + 1) continue;
        const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
        const double s = len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0;
        best = std::min(best, std::hypot(p.x - a.x - s * dx, p.y - a.y - s * dy));
    }
    return best;
}

}  // namespace

TEST_CASE("axis ticks are 1, 2 or 5 times a power of ten, and cover the range") {
    const axis degrees = over(0, 90, 5);  // 18 a step at most: 20
    CHECK(degrees.lo == 0);
    CHECK(degrees.hi == 100);
    CHECK(degrees.ticks == std::vector<double>{0, 20, 40, 60, 80, 100});
    CHECK(degrees.labels == std::vector<std::string>{"0", "20", "40", "60", "80", "100"});
    CHECK(degrees.offset == 0);

    const axis unit = over(0, 1, 5);  // 0.2 a step
    REQUIRE(unit.ticks.size() == 6);
    CHECK(unit.ticks[3] == doctest::Approx(0.6));
    CHECK(unit.labels == std::vector<std::string>{"0", "0.2", "0.4", "0.6", "0.8", "1"});

    const axis across_zero = over(-0.3, 0.7, 5);
    CHECK(across_zero.lo <= -0.3);
    CHECK(across_zero.hi >= 0.7);
    CHECK(std::count(across_zero.ticks.begin(), across_zero.ticks.end(), 0.0) == 1);  // a zero, not 5.5e-17

    const axis tiny = over(1e-7, 3e-7, 4);  // differences of a rotation's rounding: a step of 5e-8
    CHECK(tiny.labels == std::vector<std::string>{"10e-8", "15e-8", "20e-8", "25e-8", "30e-8"});
    const axis far = over(1e15, 1e15 + 100, 5);  // times from 1e15 s: labels from the first tick
    CHECK(far.offset == 1e15);
    CHECK(far.labels == std::vector<std::string>{"0", "20", "40", "60", "80", "100"});
    const axis noise = over(180, 180 + 1e-15, 5);  // a constant angle's rounding: flat, its ticks integers
    CHECK(noise.lo < 180);
    CHECK(noise.hi > 180);
    CHECK(noise.ticks.size() <= 7);
    const axis huge = over(-1e300, 1e300, 4);
    CHECK(huge.labels.front() == "-10e299");
    CHECK(huge.labels.back() == "10e299");

    // One value, or none: an interval of one unit around it.
    const axis one = over(5, 5, 5);
    CHECK(one.lo <= 4.5);
    CHECK(one.hi >= 5.5);
    const axis none = axis_of(range{}, 5);
    CHECK(none.lo == 0);
    CHECK(none.hi == 1);
}

TEST_CASE("a thinned polyline keeps every extreme and stays within half a pixel") {
    // A wave of 100,000 points over 700 pixels, with a spike one point wide.
    std::vector<point> wave;
    for (int i = 0; i < 100000; ++i) {
        const double x = 50 + 700.0 * i / 100000;
        wave.push_back({x, 200 + 80 * std::sin(x / 23) + 10 * std::sin(x * 1.7) + (i == 31337 ? -150 : 0)});
    }
    const std::vector<point> kept = thinned(wave);
    CHECK(kept.size() <= 16 * 701);
    CHECK(kept.front().x == wave.front().x);
    CHECK(kept.back().x == wave.back().x);
    const auto by_y = [](point a, point b) { return a.y < b.y; };
    CHECK(std::min_element(kept.begin(), kept.end(), by_y)->y == std::min_element(wave.begin(), wave.end(), by_y)->y);
    CHECK(std::max_element(kept.begin(), kept.end(), by_y)->y == std::max_element(wave.begin(), wave.end(), by_y)->y);
    double worst = 0;
    for (std::size_t i = 0; i < wave.size(); i += 7) worst = std::max(worst, off_line(wave[i], kept));
    CHECK(worst <= 0.45 + 1e-9);

    // A straight line is its two ends.
    CHECK(thinned(std::vector<point>{{0, 0}, {1.5, 1.5}, {2.5, 2.5}, {10, 10}}).size() == 2);
    CHECK(thinned(std::vector<point>{}).empty());
    CHECK(thinned(std::vector<point>{{3, 4}}).size() == 1);
}

TEST_CASE("a curve thinned as it comes, in its panel's terms, draws as the whole curve does") {
    // A noisy curve of 200,000 points over 50 s, and its panel's page.
    std::vector<point> whole;
    curve_thinner streamed(0, 50);
    for (int i = 0; i < 200000; ++i) {
        const point p{50.0 * i / 199999, std::sin(i / 3000.0) + 0.05 * std::sin(i * 2.3)};
        whole.push_back(p);
        streamed.add(p);
    }
    const std::vector<point> kept = streamed.finish();
    CHECK(kept.size() < 16 * 710);
    const auto on_page = [](const std::vector<point>& points) {
        std::vector<point> page;
        for (const point& p : points) page.push_back({page_x(p.x, 0, 50), 300 - 100 * p.y});
        return page;
    };
    const std::vector<point> from_whole = thinned(on_page(whole)), from_kept = thinned(on_page(kept));
    REQUIRE(from_whole.size() == from_kept.size());
    for (std::size_t i = 0; i < from_whole.size(); ++i) {
        CHECK(from_whole[i].x == from_kept[i].x);
        CHECK(from_whole[i].y == from_kept[i].y);
    }
    // One point: a unit around it.
    CHECK(page_x(3, 3, 3) == doctest::Approx((plot_left + plot_right) / 2));
}

TEST_CASE("the SVG is a standalone document, its text escaped, the same bytes each time") {
    figure f;
    panel p;
    p.title = "hip <L> & 'R' \"ok\"";
    p.x_label = "time (s)";
    p.y_label = "angle (deg)";
    p.curves.push_back({"w", colour::blue, {{0, 1}, {1, 0.5}}});
    p.marked.push_back({"keys", colour::blue, mark_shape::dot, {{0, 1}, {1, 0.5}}});
    p.levels.push_back({"tolerance", 0.75});
    f.panels.push_back(p);
    const std::string svg = to_svg(f);
    CHECK(svg.starts_with("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\""));
    CHECK(svg.find("viewBox=\"0 0 800 ") != std::string::npos);
    CHECK(svg.find("font-family=\"sans-serif\"") != std::string::npos);
    CHECK(svg.find("hip &lt;L&gt; &amp; &apos;R&apos; &quot;ok&quot;") != std::string::npos);
    CHECK(svg.find("<L>") == std::string::npos);
    CHECK(svg.find("prefers-color-scheme: dark") != std::string::npos);
    CHECK(svg.ends_with("</svg>\n"));
    CHECK(to_svg(f) == svg);
    // Each panel a group of its own.
    f.panels.push_back(p);
    const std::string two = to_svg(f);
    std::size_t groups = 0;
    for (auto at = two.find("<g class=\"panel\">"); at != std::string::npos; at = two.find("<g class=\"panel\">", at + 1))
        ++groups;
    CHECK(groups == 2);
}
