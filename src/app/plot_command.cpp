// SPDX-License-Identifier: MIT
// plot: the tracks of the inputs as an SVG picture, a panel per track (and
// one of its speed with --speed). Each input is read twice, a key at a
// time: for its tracks' spans, then to draw them; the picture is written
// once every track is drawn, and nothing before.
#include <fnmatch.h>

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>

#include "app/commands.hpp"
#include "app/plan.hpp"
#include "app/plots.hpp"
#include "io/document.hpp"

namespace keyrot::detail {

namespace {

bool wanted(const options& o, const std::string& name) {
    if (o.track_patterns.empty()) return true;
    return std::any_of(o.track_patterns.begin(), o.track_patterns.end(),
                       [&](const std::string& p) { return ::fnmatch(p.c_str(), name.c_str(), 0) == 0; });
}

/// "hip, knee, ankle", or the first ten names and how many more.
std::string names_text(const std::vector<std::string>& names) {
    constexpr std::size_t shown = 10;
    std::vector<std::string> first;
    for (std::size_t i = 0; i < std::min(shown, names.size()); ++i)
        first.push_back(names[i].empty() ? "(unnamed)" : printable(names[i]));
    std::string text = fmt::format("{}", fmt::join(first, ", "));
    if (names.size() > shown) text += fmt::format(" and {} more", names.size() - shown);
    return text;
}

/// A track as the first pass finds it.
struct outline {
    std::string name;
    track_span span;
    std::optional<euler_seq> euler;
    std::optional<track_interpolation> interpolation;
};

/// The tracks of `src`, in order of first appearance: a first pass, for
/// their spans (each curve is thinned to the columns of its panel as it is
/// drawn, which needs the panel's time axis before the first key).
std::vector<outline> outlines_of(const options& o, const input_source& src, format fmt, warnings& warn) {
    std::vector<outline> tracks;
    track_order order;
    const auto restart = [&] { tracks.clear(), order.clear(); };
    const auto each = [&](const std::string& name, const key_settings& s, key&& k) {
        const auto [at, added] = order.add(name, k, src.source());
        if (added) tracks.push_back({name, {k.time, k.time, 0}, s.euler, s.interpolation});
        tracks[at].span.last = k.time;
        ++tracks[at].span.keys;
    };
    for_each_key(src, fmt, reading(o, src.source()), warn, restart, each);
    return tracks;
}

/// The panels of the wanted tracks of `src`, drawn as a second pass reads them.
void draw_file(const options& o, const input_source& src, bool several, svg::figure& figure,
               std::vector<std::string>& names, warnings& warn) {
    const format fmt = src.detect(o.from);
    const std::vector<outline> tracks = outlines_of(o, src, fmt, warn);
    std::vector<std::optional<track_drawing>> drawings(tracks.size());
    const auto start = [&] {
        for (std::size_t i = 0; i < tracks.size(); ++i) {
            const outline& t = tracks[i];
            drawings[i].reset();
            if (!wanted(o, t.name)) continue;
            const std::string title = printable(t.name.empty()        ? src.source()
                                                : several ? src.source() + ": " + t.name
                                                          : t.name);
            // the method in force: --method, else the file's own, else slerp
            const method how = o.how.value_or(t.interpolation ? t.interpolation->rotation : method::slerp);
            drawings[i].emplace(title, t.span, t.euler, drawing_of(o, t.euler), how, o.way, o.speed);
        }
    };
    start();
    std::map<std::string, std::size_t> index;
    for (std::size_t i = 0; i < tracks.size(); ++i) index.emplace(tracks[i].name, i), names.push_back(tracks[i].name);
    std::ostringstream said;  // the first pass said it
    warnings quiet(said, src.source());
    std::string now;  // the track a cubic spline that does not settle is of
    try {
        for_each_key(src, fmt, reading(o, src.source()), quiet, start,
                     [&](const std::string& name, const key_settings&, key&& k) {
                         const auto at = index.find(name);
                         if (at == index.end()) throw error(changed_while_read(src.source()));
                         now = name;
                         if (auto& d = drawings[at->second]) d->add(k);
                     });
        for (std::size_t i = 0; i < tracks.size(); ++i) {
            now = tracks[i].name;
            if (drawings[i])
                for (svg::panel& p : drawings[i]->finish()) figure.panels.push_back(std::move(p));
        }
    } catch (const spline_error& e) {
        throw error(fmt::format("{}: {}{}", src.source(), now.empty() ? "" : fmt::format("track '{}': ", now), e.what()));
    }
}

/// The picture of every input's tracks, written to -o.
void plot(const options& o, std::istream& in, std::ostream& out, std::ostream& err) {
    picture_file picture(*o.output, o.fsync, out);
    const std::vector<std::string> inputs = input_names(o);
    svg::figure figure;
    std::vector<std::string> all_names, sources;
    for (const std::string& name : inputs) {
        const input_source src(name, in);
        sources.push_back(printable(src.source()));
        warnings warn(err, src.source());
        draw_file(o, src, inputs.size() > 1, figure, all_names, warn);
    }
    if (figure.panels.empty())
        throw error(fmt::format("--track {}: no track of {} matches: expected one of {}",
                                fmt::join(o.track_patterns, ", "), fmt::join(sources, ", "), names_text(all_names)));
    picture.write(figure);
}

}  // namespace

int run_plot(const options& o, std::istream& in, std::ostream& out, std::ostream& err) {
    if (!o.output) throw usage_error("plot: expected -o FILE.svg for the picture (-o - for standard output)");
    try {
        plot(o, in, out, err);
        return 0;
    } catch (const option_error&) {  // said in flags by run()
        throw;
    } catch (const error& e) {
        print_error(err, e.what());
        return 2;
    }
}

}  // namespace keyrot::detail
