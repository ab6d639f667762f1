// compare: a key against one answer row by row, or against several as a
// grade table, within tolerances, for grading.
#include <fmt/format.h>

#include <algorithm>
#include <ostream>
#include <sstream>
#include <string_view>
#include <unordered_set>

#include "app/commands.hpp"
#include "app/plan.hpp"
#include "io/document.hpp"
#include "io/io.hpp"
#include "io/layout.hpp"
#include "keyrot/compare.hpp"

namespace keyrot::detail {

namespace {

/// One answer graded against the key: its comparison, or why it could not
/// be read; and, where the answer fails as a whole, its likely cause.
struct grade {
    std::string file;
    std::optional<comparison> result;
    std::string error;  ///< the answer could not be read
    std::string hint;
    bool pass() const { return result && result->failed == 0; }
    std::string_view verdict() const { return !result ? "unreadable" : pass() ? "pass" : "fail"; }
};

/// Where a row is: "track hip frame 3 (0.125 s)", or by time alone when
/// the frame number is not that file's (rows matched across frame rates).
std::string row_place(const row_difference& r, bool frame = true) {
    std::string place = r.track.empty() ? "" : fmt::format("track {} ", r.track);
    if (r.frame && frame) return place + fmt::format("frame {} ({} s)", *r.frame, r.time);
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

/// The first failing row of a comparison, for the grade table.
const row_difference* first_failure(const comparison& c) {
    const auto it = std::find_if(c.rows.begin(), c.rows.end(), [](const row_difference& r) { return !r.pass(); });
    return it == c.rows.end() ? nullptr : &*it;
}

std::string number_text(std::optional<double> v) {
    std::string out;
    if (v) append_number(out, *v, std::nullopt);
    return out;
}

/// A JSON number, or null.
std::string json_number(std::optional<double> v) { return v ? number_text(v) : "null"; }

/// A file name as a JSON string (a name that is not UTF-8 printed as \xNN).
std::string json_name(std::string_view name) { return json_quote(printable(name)); }

/// One answer's report: the summary's figures and one entry per row; or,
/// for an answer that could not be read, why.
std::string json_report(const grade& g, const tolerances& tol) {
    std::string out = "{";
    if (!g.result) return fmt::format("{{\"error\": {}, \"pass\": false}}\n", json_quote(g.error));
    const comparison& c = *g.result;
    out += fmt::format("\"rows\": {}, \"failed\": {}, \"missing\": {}, \"extra\": {}, \"tolerance\": {}, "
                       "\"tolerance_translation\": {}, \"max_difference\": {}",
                       c.rows.size(), c.failed, c.missing, c.extra, number_text(tol.rotation_deg),
                       number_text(tol.translation), json_number(c.worst ? c.rows[*c.worst].angle_deg : std::nullopt));
    if (!g.hint.empty()) out += ", \"hint\": " + json_quote(g.hint);
    out += ", \"entries\": [";
    for (std::size_t i = 0; i < c.rows.size(); ++i) {
        const row_difference& r = c.rows[i];
        out += i ? ",\n" : "\n";
        out += fmt::format("{{\"track\": {}, \"frame\": {}, \"time\": {}, \"difference\": {}", json_quote(r.track),
                           json_number(r.frame), number_text(r.time), json_number(r.angle_deg));
        if (r.translation) out += ", \"translation_difference\": " + number_text(r.translation);
        if (r.scale) out += ", \"scale_difference\": " + number_text(r.scale);
        if (r.extra) out += ", \"extra\": true";
        out += fmt::format(", \"pass\": {}", r.pass() ? "true" : "false");
        if (!r.pass()) out += ", \"reason\": " + json_quote(r.problem);
        out += '}';
    }
    out += "]}\n";
    return out;
}

/// The same entries as CSV, a row each.
std::string csv_report(const comparison& c) {
    std::string out = "track,frame,time,difference,translation_difference,scale_difference,extra,pass,reason\n";
    for (const row_difference& r : c.rows) {
        append_csv_cell(out, r.track);
        out += fmt::format(",{},{},{},{},{},{},{},", number_text(r.frame), number_text(r.time),
                           number_text(r.angle_deg), number_text(r.translation), number_text(r.scale), r.extra,
                           r.pass());
        append_csv_cell(out, r.problem);
        out += '\n';
    }
    return out;
}

/// A grade table row's figures: rows, failed, missing, extra, the largest
/// difference and where, the reason it failed.
struct table_row {
    std::string rows, failed, missing, extra, largest, where, reason;
};

table_row row_of(const grade& g) {
    if (!g.result) return {"", "", "", "", "", "", g.error};
    const comparison& c = *g.result;
    table_row t{std::to_string(c.rows.size()), std::to_string(c.failed), std::to_string(c.missing),
                std::to_string(c.extra), "", "", ""};
    if (c.worst) {
        t.largest = fmt::format("{:.6g}", *c.rows[*c.worst].angle_deg);
        t.where = row_place(c.rows[*c.worst]);
    }
    if (const row_difference* r = first_failure(c)) t.reason = row_place(*r, !r->extra) + ": " + r->problem;
    if (!g.hint.empty()) t.reason += (t.reason.empty() ? "" : "; ") + g.hint;
    return t;
}

std::string grade_table_text(const std::vector<grade>& grades) {
    std::vector<std::array<std::string, 9>> cells{
        {"answer", "grade", "rows", "failed", "missing", "extra", "largest (deg)", "at", "reason"}};
    for (const grade& g : grades) {
        const table_row t = row_of(g);
        cells.push_back({printable(g.file), std::string(g.verdict()), t.rows, t.failed, t.missing, t.extra, t.largest,
                         t.where, t.reason});
    }
    std::array<std::size_t, 9> width{};
    for (const auto& row : cells)
        for (std::size_t i = 0; i < row.size(); ++i) width[i] = std::max(width[i], row[i].size());
    std::string out;
    for (const auto& row : cells) {
        std::string line;
        for (std::size_t i = 0; i < row.size(); ++i)
            line += i + 1 < row.size() ? fmt::format("{:<{}}  ", row[i], width[i]) : row[i];
        line.erase(line.find_last_not_of(' ') + 1);
        out += line + '\n';
    }
    return out;
}

std::string grade_table_csv(const std::vector<grade>& grades) {
    std::string out = "answer,grade,rows,failed,missing,extra,max_difference,track,time,reason\n";
    for (const grade& g : grades) {
        const table_row t = row_of(g);
        append_csv_cell(out, printable(g.file));
        const row_difference* worst = g.result && g.result->worst ? &g.result->rows[*g.result->worst] : nullptr;
        out += fmt::format(",{},{},{},{},{},{},", g.verdict(), t.rows, t.failed, t.missing, t.extra,
                           number_text(worst ? worst->angle_deg : std::nullopt));
        if (worst) append_csv_cell(out, worst->track);
        out += fmt::format(",{},", worst ? number_text(worst->time) : "");
        append_csv_cell(out, t.reason);
        out += '\n';
    }
    return out;
}

std::string grade_table_json(const std::string& key, const std::vector<grade>& grades, const tolerances& tol) {
    const auto count = [&](std::string_view v) {
        return std::count_if(grades.begin(), grades.end(), [&](const grade& g) { return g.verdict() == v; });
    };
    std::string out = fmt::format("{{\"key\": {}, \"tolerance\": {}, \"tolerance_translation\": {}, \"answers\": {}, "
                                  "\"pass\": {}, \"fail\": {}, \"unreadable\": {}, \"grades\": [",
                                  json_name(key), number_text(tol.rotation_deg), number_text(tol.translation),
                                  grades.size(), count("pass"), count("fail"), count("unreadable"));
    for (std::size_t i = 0; i < grades.size(); ++i) {
        const grade& g = grades[i];
        out += i ? ",\n" : "\n";
        out += fmt::format("{{\"answer\": {}, \"grade\": \"{}\"", json_name(g.file), g.verdict());
        if (!g.result) {
            out += ", \"error\": " + json_quote(g.error) + "}";
            continue;
        }
        const comparison& c = *g.result;
        const row_difference* worst = c.worst ? &c.rows[*c.worst] : nullptr;
        out += fmt::format(", \"rows\": {}, \"failed\": {}, \"missing\": {}, \"extra\": {}, \"max_difference\": {}, "
                           "\"track\": {}, \"time\": {}, \"reason\": {}",
                           c.rows.size(), c.failed, c.missing, c.extra,
                           json_number(worst ? worst->angle_deg : std::nullopt),
                           worst ? json_quote(worst->track) : "null",
                           json_number(worst ? std::optional(worst->time) : std::nullopt),
                           g.pass() && g.hint.empty() ? "null" : json_quote(row_of(g).reason));
        out += '}';
    }
    out += "]}\n";
    return out;
}

/// Whether any key of `doc` is timed by its frame number alone.
bool counted(const document& doc) {
    return std::any_of(doc.tracks.begin(), doc.tracks.end(), [](const track& t) {
        return std::any_of(t.keys.begin(), t.keys.end(), [](const key& k) { return k.frame && !k.has_time; });
    });
}

/// The answers keyrot looks at for a likely cause: no more keys than a
/// homework file, as each reading of another way costs a reading of it.
constexpr std::size_t hint_keys = 100000;

/// Where rows are both missing and extra: a frame rate that could explain it. Where matched
/// rows differ: another reading of the answer (degrees for radians
/// or the reverse, the other quaternion order, another Euler sequence) under
/// which every row passes.
std::string likely_cause(const options& o, const document& expected, const document& answer, const input_source& src,
                         const comparison& c) {
    if (c.missing > 0 && c.extra > 0 && (counted(expected) || counted(answer)))
        return fmt::format("rows missing and extra: frame numbers without times count at {} fps unless the file "
                           "states a rate; --key-fps RATE reads them at another",
                           o.key_fps.value_or(default_key_fps));
    const bool some_differ = std::any_of(c.rows.begin(), c.rows.end(),
                                         [](const row_difference& r) { return r.angle_deg && !r.pass(); });
    std::size_t keys = 0;
    std::unordered_set<rep> given;
    for (const track& t : answer.tracks) {
        keys += t.keys.size();
        for (const key& k : t.keys) given.insert(k.given_as);
    }
    if (!some_differ || keys > hint_keys) return "";
    std::vector<std::pair<options, std::string>> readings;
    if (given.contains(rep::axis_angle) || given.contains(rep::rotvec) || given.contains(rep::euler)) {
        options other = o;
        other.radians = !o.radians;
        readings.emplace_back(other, o.radians ? "read as degrees (without --radians)" : "read as radians (--radians)");
    }
    if (given.contains(rep::quat)) {
        options other = o;
        other.order = o.order == quat_order::wxyz ? quat_order::xyzw : quat_order::wxyz;
        other.order_given = true;
        readings.emplace_back(other, fmt::format("read with --quat-order {}", to_string(other.order)));
    }
    if (given.contains(rep::euler))
        for (const std::string_view axes : {"ZYX", "XYZ", "ZXY", "YXZ", "XZY", "YZX", "ZXZ", "ZYZ", "XYX", "XZX",
                                            "YXY", "YZY", "xyz", "zyx", "zxy", "yxz", "xzy", "yzx", "zxz", "zyz",
                                            "xyx", "xzx", "yxy", "yzy"}) {
            const euler_seq seq = *parse_euler_seq(axes);
            if (answer.tracks.front().euler && seq.name == answer.tracks.front().euler->name) continue;
            options other = o;
            other.euler = seq;
            readings.emplace_back(other, fmt::format("read with --euler {}", axes));
        }
    for (const auto& [other, how] : readings) {
        std::ostringstream quiet;
        warnings warn(quiet, src.source());
        try {
            const comparison again = compare_tracks(expected.tracks, read_input(other, src, warn).tracks,
                                                    {o.tol_deg, o.tol_translation}, o.extra);
            if (again.failed == 0) return fmt::format("every row is within tolerance when the answer is {}", how);
        } catch (const error&) {  // that reading is not a cause
        }
    }
    return "";
}

/// Grades one answer against `key`, warnings to `err`; an answer that
/// cannot be read is a grade, not the end of the run.
grade grade_answer(const options& o, const document& expected, const input_source& src, std::ostream& err) {
    grade g{src.source(), std::nullopt, "", ""};
    warnings warn(err, src.source());
    try {
        const document answer = read_input(o, src, warn);
        g.result = compare_tracks(expected.tracks, answer.tracks, {o.tol_deg, o.tol_translation}, o.extra);
        if (!g.pass()) g.hint = likely_cause(o, expected, answer, src, *g.result);
    } catch (const usage_error&) {
        throw;
    } catch (const error& e) {
        g.error = e.what();
    }
    return g;
}

/// One answer: its failing rows on stderr (each under the name of the file
/// whose frame number it prints), and the summary or a report.
int report_one(const options& o, const document& expected, const grade& g, std::ostream& out, std::ostream& err) {
    const tolerances tol{o.tol_deg, o.tol_translation};
    if (!g.result) {
        print_error(err, g.error);
        if (o.report == format::json) emit(o, json_report(g, tol), out);
        return 2;
    }
    const comparison& c = *g.result;
    if (c.frame_rates)
        print_error(err, fmt::format("{} counts frames at {:.6g} fps, {} at {:.6g} fps: rows are matched by time",
                                     expected.source, c.frame_rates->first, g.file, c.frame_rates->second));
    // A track missing from either file is said once, not row by row.
    constexpr std::size_t max_reasons = 10;
    std::unordered_set<std::string_view> whole_tracks;
    for (const auto& [names, where] :
         {std::pair(&c.missing_tracks, "missing from ACTUAL"), std::pair(&c.extra_tracks, "only in ACTUAL")}) {
        for (const std::string& name : *names) {
            if (whole_tracks.size() < max_reasons) print_error(err, fmt::format("{}: track '{}' {}", g.file, name, where));
            whole_tracks.insert(name);
        }
    }
    if (whole_tracks.size() > max_reasons)
        print_error(err, fmt::format("{}: {} more tracks missing from one file", g.file, whole_tracks.size() - max_reasons));
    std::size_t told = 0;
    for (const row_difference& r : c.rows) {
        if (r.pass() || whole_tracks.contains(r.track)) continue;
        // A row missing from ACTUAL is at EXPECTED's frame; a matched row
        // names its frame only where both files number frames alike.
        const bool missing = !r.angle_deg && !r.extra;
        const std::string place = missing ? expected.source + ": " + row_place(r)
                                          : g.file + ": " + row_place(r, r.extra || !c.frame_rates);
        if (told++ < max_reasons) print_error(err, place + ": " + r.problem);
    }
    if (told > max_reasons) print_error(err, fmt::format("{}: {} more rows failed", g.file, told - max_reasons));
    const std::string line = summary(c) + (g.hint.empty() ? "" : "; " + g.hint) + "\n";
    if (o.report == format::json) emit(o, json_report(g, tol), out);
    else if (o.report == format::csv) emit(o, csv_report(c), out);
    if (o.report) err << line;  // (standard output holds the report alone)
    else emit(o, line, out);
    return c.failed ? 1 : 0;
}

}  // namespace

int run_compare(const options& o, std::istream& in, std::ostream& out, std::ostream& err) {
    if (o.inputs.size() < 2) throw usage_error("compare: ANSWER is missing: expected the key, then one answer or more");
    if (std::count_if(o.inputs.begin(), o.inputs.end(), [](const auto& f) { return is_standard_stream(f); }) > 1)
        throw usage_error("compare: only one of KEY and the answers can be '-'");
    const input_source key_src(o.inputs[0], in);
    warnings warn_key(err, key_src.source());
    const document expected = read_input(o, key_src, warn_key);
    std::vector<grade> grades;
    for (std::size_t i = 1; i < o.inputs.size(); ++i) {
        const input_source src(o.inputs[i], in);
        grades.push_back(grade_answer(o, expected, src, err));
        if (o.inputs.size() == 2) return report_one(o, expected, grades.back(), out, err);
    }
    // A grade table: a row per answer; the hints and the count on stderr.
    const tolerances tol{o.tol_deg, o.tol_translation};
    if (o.report == format::json) emit(o, grade_table_json(expected.source, grades, tol), out);
    else if (o.report == format::csv) emit(o, grade_table_csv(grades), out);
    else emit(o, grade_table_text(grades), out);
    std::size_t passed = 0, unreadable = 0;
    for (const grade& g : grades) {
        passed += g.pass();
        unreadable += !g.result;
        if (!g.result) print_error(err, g.error);
    }
    err << fmt::format("{} answers graded against {}: {} pass, {} fail, {} unreadable\n", grades.size(),
                       printable(expected.source), passed, grades.size() - passed - unreadable, unreadable);
    return passed == grades.size() ? 0 : 1;
}

}  // namespace keyrot::detail
