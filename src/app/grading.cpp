// The grading and teaching commands: slerp, compare, info.
#include <fmt/format.h>

#include <algorithm>
#include <ostream>
#include <string_view>
#include <unordered_set>

#include "app/commands.hpp"
#include "keyrot/compare.hpp"
#include "keyrot/describe.hpp"
#include "io/layout.hpp"
#include "fast/row_pipeline.hpp"

namespace keyrot::detail {

// ---------------------------------------------------------------- slerp

namespace {

/// A slerp operand ("0,0,0.7071,0.7071") as a key at `time`.
raw_key operand(const char* name, const std::string& text, const options& o, double time) {
    raw_key k;
    k.time = time;
    k.kind = o.from_rep;
    const std::size_t want = o.from_rep == rep::rotvec || o.from_rep == rep::euler ? 3 : 4;
    std::vector<double> values;
    std::string_view rest = text;
    while (true) {
        const auto comma = rest.find(',');
        const auto v = parse_number(rest.substr(0, comma));
        if (!v) break;
        values.push_back(*v);
        if (comma == std::string_view::npos) break;
        rest.remove_prefix(comma + 1);
        if (values.size() > want) break;
    }
    const bool complete = values.size() == want && (rest.find(',') == std::string_view::npos);
    if (!complete) {
        const char* what = o.from_rep == rep::quat         ? (o.order == quat_order::wxyz ? "w,x,y,z" : "x,y,z,w")
                           : o.from_rep == rep::axis_angle ? "ax,ay,az,angle"
                           : o.from_rep == rep::rotvec     ? "rx,ry,rz"
                                                           : "e1,e2,e3";
        throw usage_error(fmt::format("{}: expected {} comma-separated numbers ({}, --from-rep {}), got '{}'", name, want,
                                      what, to_string(o.from_rep), excerpt(text)));
    }
    if (o.from_rep == rep::quat) {
        const auto wxyz = from_quat_order({values[0], values[1], values[2], values[3]}, o.order);
        std::copy(wxyz.begin(), wxyz.end(), k.values.begin());
    } else {
        std::copy(values.begin(), values.end(), k.values.begin());
    }
    return k;
}

}  // namespace

int run_slerp(const options& o, std::ostream& out, std::ostream& err) {
    if (o.how == method::squad) throw usage_error("--method squad needs more than two keys: use resample");
    if (o.steps) {
        if (*o.steps < 1) throw usage_error(fmt::format("--steps: expected at least 1, got {}", *o.steps));
        // A mistyped count must not write for hours.
        if (*o.steps + 1.0 > o.max_frames)
            throw usage_error(fmt::format("--steps {} makes {} rows: expected at most {:g} (--max-frames N raises the limit)",
                                          *o.steps, *o.steps + 1.0, o.max_frames));
    }
    if (o.ts.empty() && !o.steps) throw usage_error("slerp needs -t T or --steps N");
    // Each operand is its own source for messages: "keyrot: Q1: quaternion is zero: ...".
    warnings warn0(err, "Q0"), warn1(err, "Q1");
    const track t{"", o.euler, {make_key(operand("Q0", o.q0, o, 0), settings_of(o), warn0),
                                make_key(operand("Q1", o.q1, o, 1), settings_of(o), warn1)}};
    const rotation_curve curve(t, o.how, o.way);
    table_info info;
    info.times = time_columns::time_only;
    info.time_name = "t";
    info.method = to_string(o.how);
    // Rows are written as they are made: --steps may ask for millions.
    const std::optional<std::string> target = o.output && *o.output != "-" ? o.output : std::nullopt;
    chunked_output sink(target, out);
    const format to = o.to.value_or(target ? format_of_path(*target).value_or(format::csv) : format::csv);
    const auto writer = make_writer(to, sink.text(), info, output_settings(o, t.euler), warn0);
    writer->begin_track("", false);
    const auto row = [&](double h) {
        const quat q = h == 0 ? curve.at_key(0) : h == 1 ? curve.at_key(1) : curve.at(0, h);
        writer->row(sample{h, std::nullopt, q, std::nullopt});
        sink.maybe_flush();
    };
    for (double h : o.ts) row(h);
    if (o.steps)
        for (int i = 0; i <= *o.steps; ++i) row(static_cast<double>(i) / *o.steps);
    writer->finish();
    sink.finish();
    return 0;
}

// ---------------------------------------------------------------- compare

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
    if (o.inputs[0] == "-" && o.inputs[1] == "-") throw usage_error("compare: only one of EXPECTED and ACTUAL can be '-'");
    const input_source expected_src(o.inputs[0], in), actual_src(o.inputs[1], in);
    warnings warn_e(err, expected_src.source()), warn_a(err, actual_src.source());
    const input expected = load(o, expected_src, warn_e, json_reading::streamed_first);
    const input actual = load(o, actual_src, warn_a, json_reading::streamed_first);
    const tolerances tol{o.tol_deg, o.tol_translation};
    const comparison c = compare_tracks(expected.tracks, actual.tracks, tol);

    if (c.frame_rates)
        print_error(err, fmt::format("{} counts frames at {} fps, {} at {} fps: rows are matched by time",
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

// ---------------------------------------------------------------- info

namespace {

std::string index_list(const std::vector<std::size_t>& v) {
    return v.empty() ? std::string("none") : fmt::format("{}", fmt::join(v, ", "));
}

std::string rep_list(const std::vector<rep>& reps) {
    std::vector<std::string_view> names;
    for (rep r : reps) names.push_back(to_string(r));
    return fmt::format("{}", fmt::join(names, ", "));
}

std::string info_text(const input& doc, const std::vector<track_info>& infos, std::optional<int> precision) {
    auto num = [precision](double v) {
        std::string s;
        append_number(s, v, precision.value_or(6));
        return s;
    };
    // (printable: a file name's control bytes must not reach a terminal raw)
    std::string out = fmt::format("{}: {} track{}, {}\n", printable(doc.source), infos.size(), infos.size() == 1 ? "" : "s",
                                  to_string(doc.fmt));
    for (const track_info& t : infos) {
        out += fmt::format("{}: {} key{}, {} s to {} s, given as {}\n", t.name.empty() ? "track" : "track " + t.name,
                           t.keys, t.keys == 1 ? "" : "s", num(t.start), num(t.end), rep_list(t.given_as));
        for (std::size_t i = 0; i < t.segments.size(); ++i) {
            const segment_info& s = t.segments[i];
            if (i == 0) out += "  segment  angle (deg)  speed (deg/s)\n";
            const bool long_way = s.direct_long_way && t.signed_keys;
            out += fmt::format("  {:<7}  {:<11}  {}{}\n", fmt::format("{}-{}", i, i + 1), num(s.angle_deg),
                               num(s.speed_deg_s), long_way ? "  (long way with --path direct)" : "");
        }
        if (t.signed_keys) out += fmt::format("  keys flipped by --path shortest: {}\n", index_list(t.flipped));
        out += fmt::format("  keys renormalised: {}\n", index_list(t.renormalised));
        out += fmt::format("  Euler keys within {} deg of gimbal lock: {}\n", near_gimbal_deg, index_list(t.near_gimbal));
    }
    return out;
}

std::string info_json(const input& doc, const std::vector<track_info>& infos) {
    auto num = [](double v) {
        std::string s;
        append_number(s, v, std::nullopt);
        return s;
    };
    auto list = [](const std::vector<std::size_t>& v) { return fmt::format("[{}]", fmt::join(v, ", ")); };
    std::string out = "{\"source\": " + json_quote(doc.source) + ", \"format\": \"" +
                      std::string(to_string(doc.fmt)) + "\", \"tracks\": [";
    for (std::size_t n = 0; n < infos.size(); ++n) {
        const track_info& t = infos[n];
        std::vector<std::string> reps, segments;
        for (rep r : t.given_as) reps.push_back(fmt::format("\"{}\"", to_string(r)));
        for (const segment_info& s : t.segments)
            segments.push_back(fmt::format("{{\"angle\": {}, \"speed\": {}, \"direct_long_way\": {}}}", num(s.angle_deg),
                                           num(s.speed_deg_s), t.signed_keys ? fmt::format("{}", s.direct_long_way) : "null"));
        out += fmt::format(
            "{}\n{{\"name\": {}, \"keys\": {}, \"start\": {}, \"end\": {}, \"given_as\": [{}], \"segments\": [{}], "
            "\"flipped\": {}, \"renormalised\": {}, \"near_gimbal_lock\": {}}}",
            n ? "," : "", json_quote(t.name), t.keys, num(t.start), num(t.end), fmt::join(reps, ", "),
            fmt::join(segments, ", "), t.signed_keys ? list(t.flipped) : "null", list(t.renormalised), list(t.near_gimbal));
    }
    out += "]}\n";
    return out;
}

}  // namespace

int run_info(const options& o, std::istream& in, std::ostream& out, std::ostream& err) {
    const std::vector<std::string> inputs = o.inputs.empty() ? std::vector<std::string>{"-"} : o.inputs;
    const bool as_json = o.to == format::json || (o.output && format_of_path(*o.output) == format::json);
    std::string text;
    int status = 0;
    for (const std::string& name : inputs) {
        try {
            const input_source src(name, in);
            warnings warn(err, src.source());
            const input doc = load(o, src, warn, json_reading::streamed_first);
            std::vector<track_info> infos;
            for (const track& t : doc.tracks) infos.push_back(describe(t));
            text += as_json ? info_json(doc, infos) : info_text(doc, infos, o.precision);
        } catch (const usage_error&) {
            throw;
        } catch (const error& e) {
            print_error(err, e.what());
            status = 2;
        }
    }
    emit(o, text, out);
    return status;
}

}  // namespace keyrot::detail
