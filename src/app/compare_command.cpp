// SPDX-License-Identifier: MIT
// compare: a key against one answer row by row, or against several as a
// grade table, within tolerances, for grading. The files are read as
// compare_files reads them, a row at a time; reports are written as rows
// are settled.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <exception>
#include <ostream>
#include <sstream>
#include <thread>
#include <string_view>
#include <unordered_set>

#include "app/commands.hpp"
#include "app/compare_files.hpp"
#include "app/compare_hints.hpp"
#include "app/plan.hpp"
#include "app/plots.hpp"
#include "ground/thread_start.hpp"
#include "io/common/interface.hpp"
#include "io/common/layout.hpp"
#include "io/csv/csv.hpp"
#include "io/json/json.hpp"
#include "io/json/json_object.hpp"

namespace keyrot::detail {

namespace {

/// One answer graded against the key: its comparison, or why it could not
/// be read; and, where the answer fails as a whole, its likely cause.
struct grade {
    std::string file;
    std::optional<comparison_summary> result;
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

std::string summary(const comparison_summary& c) {
    std::string s = fmt::format("{} rows compared, {} failed", c.compared, c.failed);
    if (c.worst) s += fmt::format("; largest difference {:.6g} deg at {}", *c.worst->angle_deg, row_place(*c.worst));
    return s;
}

std::string number_text(std::optional<double> v) {
    std::string out;
    if (v) append_number(out, *v, std::nullopt);
    return out;
}

/// A file name as a JSON string (a name that is not UTF-8 printed as \xNN).
std::string json_name(std::string_view name) { return json_quote(printable(name)); }

std::optional<double> worst_angle(const comparison_summary& c) {
    return c.worst ? c.worst->angle_deg : std::nullopt;
}

/// An answer's first pass: its survey, or the error that stopped it.
struct answer_survey {
    std::optional<surveyed_file> file;
    std::exception_ptr failed;
};

answer_survey survey_answer(const options& o, const input_source& src, warnings& warn) {
    answer_survey s;
    try {
        s.file = survey_file(o, src, warn);
    } catch (...) {
        s.failed = std::current_exception();
    }
    return s;
}

/// Grades one answer, surveyed before, against the key; an answer that
/// cannot be read is a grade, not the end of the run. `begin` and `row` as
/// compare_files's.
grade grade_answer(const options& o, const input_source& key_src, const surveyed_file& key, const input_source& src,
                   const answer_survey& answer, const std::function<void(const comparison_summary&)>& begin = nullptr,
                   const comparer::row_sink& row = nullptr) {
    grade g{src.source(), std::nullopt, "", ""};
    try {
        if (answer.failed) std::rethrow_exception(answer.failed);
        g.result = compare_files(o, key_src, key, o, src, *answer.file, begin, row);
        if (!g.pass()) g.hint = likely_cause(o, key_src, key, src, *answer.file, *g.result);
    } catch (const option_error&) {  // the whole run's
        throw;
    } catch (const error& e) {
        g.error = e.what();
    }
    return g;
}

/// One answer's report, written as its rows are settled: its failing rows
/// on stderr (each under the name of the file whose frame number it
/// prints), then the summary; or, with --report, every row on stdout.
class one_answer_report {
public:
    one_answer_report(const options& o, const std::string& key, const std::string& answer, std::ostream& out,
                      std::ostream& err)
        : o_(o), key_(key), answer_(answer), err_(err) {
        if (o.report) to_.emplace(o, out);
    }

    /// What is known before the first row: frame rates, whole tracks missing.
    void begin(const comparison_summary& c) {
        frame_rates_ = c.frame_rates.has_value();
        if (c.frame_rates)
            print_error(err_, fmt::format("{} counts frames at {:.6g} fps, {} at {:.6g} fps: rows are matched by time",
                                          key_, c.frame_rates->first, answer_, c.frame_rates->second));
        // A track missing from either file is said once, not row by row; one
        // named as the key's but for case, once as that.
        for (const auto& [of_key, of_answer] : tracks_named_in_another_case(c)) {
            if (whole_tracks_.size() < max_reasons)
                print_error(err_, fmt::format("{}: track '{}' is the key's '{}' in another case: expected the key's "
                                              "track names (its rows are missing and extra)",
                                              answer_, of_answer, of_key));
            whole_tracks_.insert(of_key), whole_tracks_.insert(of_answer);
        }
        for (const auto& [names, where] :
             {std::pair(&c.missing_tracks, "missing from the answer"), std::pair(&c.extra_tracks, "only in the answer")}) {
            for (const std::string& name : *names) {
                if (whole_tracks_.contains(name)) continue;
                if (whole_tracks_.size() < max_reasons)
                    print_error(err_, fmt::format("{}: track '{}' {}", answer_, name, where));
                whole_tracks_.insert(name);
            }
        }
        if (whole_tracks_.size() > max_reasons)
            print_error(err_, fmt::format("{}: {} more tracks missing from one file", answer_,
                                          whole_tracks_.size() - max_reasons));
        weights_ = c.weights;
        if (o_.report == format::csv)
            to_->write(fmt::format("track,frame,time,difference,translation_difference,scale_difference,{}{}{}extra,"
                                   "pass,reason\n",
                                   weights_ ? "weights_difference," : "",
                                   o_.tol_velocity ? "velocity_difference," : "",
                                   o_.tol_acceleration ? "acceleration_difference," : ""));
        else if (o_.report == format::json)
            to_->write("{\"entries\": [");
    }

    void row(const row_difference& r) {
        if (o_.report == format::csv) return csv_row(r);
        if (o_.report == format::json) return json_row(r);
        if (r.pass() || whole_tracks_.contains(r.track)) return;
        // A row missing from the answer is at the key's frame; a matched row
        // names its frame only where both files number frames alike.
        const bool missing = !r.angle_deg && !r.extra;
        const std::string place =
            missing ? key_ + ": " + row_place(r) : answer_ + ": " + row_place(r, r.extra || !frame_rates_);
        if (told_++ < max_reasons) print_error(err_, place + ": " + r.problem);
    }

    /// The summary, and the end of the report.
    int finish(const grade& g, std::ostream& out) {
        const comparison_summary& c = *g.result;
        if (told_ > max_reasons) print_error(err_, fmt::format("{}: {} more rows failed", answer_, told_ - max_reasons));
        const std::string line = summary(c) + (g.hint.empty() ? "" : "; " + g.hint) + "\n";
        if (!o_.report) {
            emit(o_, line, out);
        } else {
            if (o_.report == format::json) {
                json_object end;  // the members after "entries"
                end.count("rows", c.compared).count("failed", c.failed).count("missing", c.missing);
                end.count("extra", c.extra).number("tolerance", o_.tol_deg).number("tolerance_translation", o_.tol_translation);
                end.number("max_difference", worst_angle(c)).flag("pass", g.pass());
                if (!g.hint.empty()) end.text("hint", g.hint);
                to_->write("], " + end.members() + "}\n");
            }
            to_->finish();
            err_ << line;  // (standard output holds the report alone)
        }
        return c.failed ? 1 : 0;
    }

private:
    void csv_row(const row_difference& r) {
        std::string line;
        append_csv_cell(line, r.track);
        line += fmt::format(",{},{},{},{},{},", number_text(r.frame), number_text(r.time), number_text(r.angle_deg),
                            number_text(r.translation), number_text(r.scale));
        if (weights_) line += number_text(r.weights) + ',';
        if (o_.tol_velocity) line += number_text(r.velocity) + ',';
        if (o_.tol_acceleration) line += number_text(r.acceleration) + ',';
        line += fmt::format("{},{},", r.extra, r.pass());
        append_csv_cell(line, r.problem);
        to_->write(line + '\n');
    }
    void json_row(const row_difference& r) {
        json_object entry;
        entry.text("track", r.track).number("frame", r.frame).number("time", r.time).number("difference", r.angle_deg);
        if (r.translation) entry.number("translation_difference", r.translation);
        if (r.scale) entry.number("scale_difference", r.scale);
        if (r.weights) entry.number("weights_difference", r.weights);
        if (r.velocity) entry.number("velocity_difference", r.velocity);
        if (r.acceleration) entry.number("acceleration_difference", r.acceleration);
        if (r.extra) entry.flag("extra", true);
        entry.flag("pass", r.pass());
        if (!r.pass()) entry.text("reason", r.problem);
        to_->write((entries_++ ? ",\n" : "\n") + entry.object());
    }

    static constexpr std::size_t max_reasons = 10;
    const options& o_;
    std::string key_, answer_;
    std::ostream& err_;
    std::optional<text_output> to_;
    std::unordered_set<std::string> whole_tracks_;
    bool frame_rates_ = false;
    bool weights_ = false;  // a weights_difference column
    std::size_t told_ = 0, entries_ = 0;
};

/// One answer against the key: both surveyed at once (the answer on a
/// thread of its own, its warnings said after the key's), then its rows as
/// they are settled (and drawn, with `picture`), then the summary.
int compare_one(const options& o, const input_source& key_src, const input_source& src, std::ostream& out,
                std::ostream& err, picture_file* picture) {
    std::ostringstream held;
    warnings key_warn(err, key_src.source()), answer_warn(err, src.source()), answer_held(held, src.source());
    answer_survey answer;
    std::thread t;
    const bool alongside = try_start_thread(t, [&] { answer = survey_answer(o, src, answer_held); });
    std::optional<surveyed_file> key;
    try {
        key = survey_file(o, key_src, key_warn);
    } catch (...) {
        if (alongside) t.join();
        throw;
    }
    if (alongside) t.join();
    else answer = survey_answer(o, src, answer_held);
    answer_warn.adopt(answer_held, held.str());

    one_answer_report report(o, key_src.source(), src.source(), out, err);
    difference_plot drawn(o.tol_deg);
    const grade g = grade_answer(
        o, key_src, *key, src, answer, [&](const comparison_summary& c) { report.begin(c); },
        [&](const row_difference& r) {
            report.row(r);
            if (picture) drawn.row(r);
        });
    if (g.result) {
        const int status = report.finish(g, out);
        if (picture) picture->write({drawn.panels("")});
        return status;
    }
    print_error(err, g.error);
    if (o.report == format::json) emit(o, json_object().text("error", g.error).flag("pass", false).object() + '\n', out);
    return 2;
}

/// A grade table row's figures: rows, failed, missing, extra, the largest
/// difference and where, the reason it failed.
struct table_row {
    std::string rows, failed, missing, extra, largest, where, reason;
};

table_row row_of(const grade& g) {
    if (!g.result) return {"", "", "", "", "", "", g.error};
    const comparison_summary& c = *g.result;
    table_row t{std::to_string(c.compared), std::to_string(c.failed), std::to_string(c.missing),
                std::to_string(c.extra), "", "", ""};
    if (c.worst) {
        t.largest = fmt::format("{:.6g}", *c.worst->angle_deg);
        t.where = row_place(*c.worst);
    }
    if (const auto& r = c.first_failure) t.reason = row_place(*r, !r->extra) + ": " + r->problem;
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
        const row_difference* worst = g.result && g.result->worst ? &*g.result->worst : nullptr;
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
        return static_cast<std::size_t>(
            std::count_if(grades.begin(), grades.end(), [&](const grade& g) { return g.verdict() == v; }));
    };
    json_object table;
    table.raw("key", json_name(key)).number("tolerance", tol.rotation_deg).number("tolerance_translation", tol.translation);
    table.count("answers", grades.size()).count("pass", count("pass")).count("fail", count("fail"));
    table.count("unreadable", count("unreadable"));
    std::string each = "[";
    for (std::size_t i = 0; i < grades.size(); ++i) {
        const grade& g = grades[i];
        json_object row;
        row.raw("answer", json_name(g.file)).text("grade", g.verdict());
        if (!g.result) {
            row.text("error", g.error);
        } else {
            const comparison_summary& c = *g.result;
            const row_difference* worst = c.worst ? &*c.worst : nullptr;
            row.count("rows", c.compared).count("failed", c.failed).count("missing", c.missing).count("extra", c.extra);
            row.number("max_difference", worst ? worst->angle_deg : std::nullopt);
            row.raw("track", worst ? json_quote(worst->track) : "null");
            row.number("time", worst ? std::optional(worst->time) : std::nullopt);
            row.raw("reason", g.pass() && g.hint.empty() ? "null" : json_quote(row_of(g).reason));
        }
        each += (i ? ",\n" : "\n") + row.object();
    }
    return table.raw("grades", each + ']').object() + '\n';
}

}  // namespace

int run_compare(const options& o, std::istream& in, std::ostream& out, std::ostream& err) {
    if (o.inputs.size() < 2)
        throw usage_error("compare: ANSWER is missing: expected the key, then one answer or more (see keyrot compare --help)");
    if (std::count_if(o.inputs.begin(), o.inputs.end(), [](const auto& f) { return is_standard_stream(f); }) > 1)
        throw usage_error("compare: only one of KEY and the answers can be '-'");
    std::optional<picture_file> picture;
    if (o.plot) picture.emplace(*o.plot, o.fsync, out);
    const input_source key_src(o.inputs[0], in);
    if (o.inputs.size() == 2) {
        const input_source src(o.inputs[1], in);
        return compare_one(o, key_src, src, out, err, picture ? &*picture : nullptr);
    }
    warnings warn_key(err, key_src.source());
    const surveyed_file key = survey_file(o, key_src, warn_key);
    // A grade table: a row per answer; the hints and the count on stderr.
    std::vector<grade> grades;
    svg::figure drawn;  // with --plot, each answer's panels in turn
    for (std::size_t i = 1; i < o.inputs.size(); ++i) {
        const input_source src(o.inputs[i], in);
        warnings warn(err, src.source());
        difference_plot rows(o.tol_deg);
        grades.push_back(grade_answer(o, key_src, key, src, survey_answer(o, src, warn), nullptr,
                                      picture ? [&](const row_difference& r) { rows.row(r); } : comparer::row_sink()));
        if (grades.back().result)
            for (svg::panel& p : rows.panels(printable(src.source()) + ": ")) drawn.panels.push_back(std::move(p));
    }
    const tolerances tol{o.tol_deg, o.tol_translation, o.tol_velocity, o.tol_acceleration};
    if (o.report == format::json) emit(o, grade_table_json(key.source, grades, tol), out);
    else if (o.report == format::csv) emit(o, grade_table_csv(grades), out);
    else emit(o, grade_table_text(grades), out);
    std::size_t passed = 0, unreadable = 0;
    for (const grade& g : grades) {
        passed += g.pass();
        unreadable += !g.result;
        if (!g.result) print_error(err, g.error);
    }
    err << fmt::format("{} answers graded against {}: {} pass, {} fail, {} unreadable\n", grades.size(),
                       printable(key.source), passed, grades.size() - passed - unreadable, unreadable);
    if (picture) picture->write(drawn);
    return passed == grades.size() ? 0 : 1;
}

}  // namespace keyrot::detail
