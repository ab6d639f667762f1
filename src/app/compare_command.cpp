// compare: two inputs row by row, within tolerances, for grading.
#include <fmt/format.h>

#include <ostream>
#include <string_view>
#include <unordered_set>

#include "app/commands.hpp"
#include "app/plan.hpp"
#include "io/document.hpp"
#include "io/layout.hpp"
#include "keyrot/compare.hpp"

namespace keyrot::detail {

namespace {

std::string row_place(const row_difference& r) {
    std::string place = r.track.empty() ? "" : fmt::format("track {} ", r.track);
    if (r.frame) return place + fmt::format("frame {} ({} s)", *r.frame, r.time);
    return place + fmt::format("time {} s", r.time);
}

std::string summary(const comparison& c) {
    std::string s = fmt::format("{} rows compared, {} failed", c.rows.size(), c.failed);
    if (c.worst) {
        const row_difference& w = c.rows[*c.worst];
        s += fmt::format("; largest difference {:.6g} deg at {}", *w.angle_deg, row_place(w));
    }
    return s;
}

std::string json_report(const comparison& c, const tolerances& tol) {
    std::string out = "{";
    auto number = [&out](double v) { append_number(out, v, std::nullopt); };
    out += fmt::format("\"rows\": {}, \"failed\": {}, \"tolerance\": ", c.rows.size(), c.failed);
    number(tol.rotation_deg);
    out += ", \"tolerance_translation\": ";
    number(tol.translation);
    out += ", \"max_difference\": ";
    if (c.worst) number(*c.rows[*c.worst].angle_deg);
    else out += "null";
    out += ", \"entries\": [";
    for (std::size_t i = 0; i < c.rows.size(); ++i) {
        const row_difference& r = c.rows[i];
        out += i ? ",\n" : "\n";
        out += "{\"track\": " + json_quote(r.track) + ", \"frame\": ";
        if (r.frame) number(*r.frame);
        else out += "null";
        out += ", \"time\": ";
        number(r.time);
        out += ", \"difference\": ";
        if (r.angle_deg) number(*r.angle_deg);
        else out += "null";
        if (r.translation) out += ", \"translation_difference\": ", number(*r.translation);
        if (r.scale) out += ", \"scale_difference\": ", number(*r.scale);
        out += fmt::format(", \"pass\": {}", r.pass() ? "true" : "false");
        if (!r.pass()) out += ", \"reason\": " + json_quote(r.problem);
        out += '}';
    }
    out += "]}\n";
    return out;
}

}  // namespace

int run_compare(const options& o, std::istream& in, std::ostream& out, std::ostream& err) {
    if (o.inputs.size() != 2) throw usage_error("compare needs two files: EXPECTED ACTUAL");
    if (is_standard_stream(o.inputs[0]) && is_standard_stream(o.inputs[1])) throw usage_error("compare: only one of EXPECTED and ACTUAL can be '-'");
    const input_source expected_src(o.inputs[0], in), actual_src(o.inputs[1], in);
    warnings warn_e(err, expected_src.source()), warn_a(err, actual_src.source());
    const document expected = read_input(o, expected_src, warn_e);
    const document actual = read_input(o, actual_src, warn_a);
    const tolerances tol{o.tol_deg, o.tol_translation};
    const comparison c = compare_tracks(expected.tracks, actual.tracks, tol);

    if (c.frame_rates)
        print_error(err, fmt::format("{} counts frames at {:.6g} fps, {} at {:.6g} fps: rows are matched by time",
                                     expected.source, c.frame_rates->first, actual.source, c.frame_rates->second));
    // A track missing from either file is said once, not row by row.
    constexpr std::size_t max_reasons = 10;
    std::unordered_set<std::string_view> whole_tracks;
    for (const auto& [names, where] :
         {std::pair(&c.missing_tracks, "missing from ACTUAL"), std::pair(&c.extra_tracks, "only in ACTUAL")}) {
        for (const std::string& name : *names) {
            if (whole_tracks.size() < max_reasons)
                print_error(err, fmt::format("{}: track '{}' {}", actual.source, name, where));
            whole_tracks.insert(name);
        }
    }
    if (whole_tracks.size() > max_reasons)
        print_error(err, fmt::format("{}: {} more tracks missing from one file", actual.source, whole_tracks.size() - max_reasons));
    std::size_t told = 0;
    for (const row_difference& r : c.rows) {
        if (r.pass() || whole_tracks.contains(r.track)) continue;
        if (told++ < max_reasons) print_error(err, actual.source + ": " + row_place(r) + ": " + r.problem);
    }
    if (told > max_reasons) print_error(err, fmt::format("{}: {} more rows failed", actual.source, told - max_reasons));
    if (o.report_json) {
        emit(o, json_report(c, tol), out);
        err << summary(c) << '\n';
    } else {
        emit(o, summary(c) + "\n", out);
    }
    return c.failed ? 1 : 0;
}

}  // namespace keyrot::detail
