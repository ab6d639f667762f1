#include "keyrot/app.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <future>
#include <mutex>
#include <thread>
#include <iostream>
#include <iterator>
#include <set>
#include <sstream>

#include "keyrot/compare.hpp"
#include "keyrot/describe.hpp"
#include "keyrot/output.hpp"
#include "keyrot/resample.hpp"
#include "keyrot/source.hpp"

namespace keyrot {
namespace {

key_settings settings_of(const options& o) {
    return {o.radians ? angle_unit::radians : angle_unit::degrees, o.euler, o.key_fps.value_or(o.fps), o.strict};
}

read_options reading(const options& o, const input_source& src) {
    read_options ro;
    ro.source = src.source();
    ro.settings = settings_of(o);
    ro.order = o.order;
    return ro;
}

write_options output_settings(const options& o, const std::optional<euler_seq>& input_euler) {
    write_options w;
    w.representation = o.representation;
    w.angles = o.out_angles.value_or(o.radians ? angle_unit::radians : angle_unit::degrees);
    w.order = o.order;
    w.precision = o.precision;
    if (w.representation == rep::euler) {
        // --out-euler, else the input's sequence (--euler or the document's own).
        w.euler = o.out_euler ? o.out_euler : input_euler;
        if (!w.euler) throw usage_error("--rep euler needs an Euler sequence: expected --out-euler SEQ or --euler SEQ");
    }
    return w;
}

resample_options resampling(const options& o) {
    resample_options r;
    r.fps = o.fps;
    r.how = o.how;
    r.way = o.way;
    r.max_frames = o.max_frames;
    return r;
}

/// An input read whole: tracks in memory (compare, info, JSON input, and
/// line-based input whose tracks are interleaved).
struct input {
    std::string source;
    format fmt = format::csv;
    bool named = false;
    std::vector<track> tracks;
};

input load(const options& o, const input_source& src, warnings& warn) {
    input result{src.source(), src.detect(o.from), false, {}};
    const auto stream = src.open();
    const raw_document doc = read_document(*stream, result.fmt, reading(o, src), warn);
    result.named = doc.named;
    result.tracks.reserve(doc.tracks.size());
    for (const raw_track& raw : doc.tracks) result.tracks.push_back(make_track(raw, warn));
    return result;
}

/// What a writer must know of a document before its first row, and what
/// each track needs before its first frame, gathered key by key.
struct document_facts {
    struct track_facts {
        std::string name;
        key first, last;
        bool translation = false;
        std::optional<euler_seq> euler;
        std::size_t keys = 0;
    };
    std::vector<track_facts> tracks;
    bool named = false;
    bool all_frames = true;  // every key has a frame
    bool any_time = false;   // some key has a time
    bool frames = false;     // some key has both: keyrot's own frames

    void add(const std::string& track, const std::optional<euler_seq>& euler, key k) {
        all_frames = all_frames && k.frame.has_value();
        any_time = any_time || k.has_time;
        frames = frames || (k.frame && k.has_time);
        if (tracks.empty() || tracks.back().name != track) tracks.push_back({track, k, k, false, euler, 0});
        ++tracks.back().keys;
        tracks.back().translation = tracks.back().translation || k.translation.has_value();
        tracks.back().last = std::move(k);
    }

    table_info table(const options& o) const {
        table_info info;
        info.named = named;
        for (const auto& t : tracks) info.translation = info.translation || t.translation;
        if (o.cmd == command::resample) {
            info.fps = o.fps;
            info.how = o.how;
        } else {
            info.times = time_columns::as_given;
            info.all_frames = all_frames;
            info.any_time = any_time;
            info.rows_name = frames ? "frames" : "keys";
        }
        return info;
    }

    /// About how many rows the output will have.
    double rows(const options& o) const {
        double n = 0;
        for (const auto& t : tracks)
            n += o.cmd == command::resample ? (t.last.time - t.first.time) * o.fps + 1 : static_cast<double>(t.keys);
        return n;
    }

    /// resample: the frame grid of every track is within bounds.
    void check(const options& o, const std::string& source) const {
        if (o.cmd != command::resample) return;
        for (const auto& t : tracks) {
            check_method(o.how, t.euler);
            check_frame_range(t.first, t.last, t.name, resampling(o), source);
        }
    }
};

document_facts facts_of(const input& doc) {
    document_facts d;
    d.named = doc.named;
    for (const track& t : doc.tracks)
        for (const key& k : t.keys) d.add(t.name, t.euler, k);
    return d;
}

/// Pass 1 over a line-based input: every key validated, the facts learnt.
/// Stops early (interleaved = true) when a track comes back after another
/// one began: such input is then read whole.
document_facts scan(const options& o, const input_source& src, format f, warnings& warn, bool& interleaved) {
    const auto stream = src.open();
    const read_options ro = reading(o, src);
    const auto reader = make_key_reader(*stream, f, ro, warn);
    document_facts d;
    std::set<std::string> seen;
    std::string name;
    raw_key raw;
    interleaved = false;
    while (reader->next(name, raw)) {
        key k = make_key(raw, ro.settings, warn);
        if (!d.tracks.empty() && d.tracks.back().name == name) {
            check_order(d.tracks.back().last, k, src.source());
        } else if (!seen.insert(name).second) {
            interleaved = true;
            return d;
        }
        d.add(name, ro.settings.euler, std::move(k));
    }
    if (d.tracks.empty()) throw input_error(where(src.source(), reader->start()), "no keys: expected at least one key");
    d.named = reader->named();
    return d;
}

/// Where output text goes: -o FILE (a temporary file renamed on success) or
/// a stream, in chunks of about a megabyte. A full chunk is written by a
/// second thread while the writer fills the next one.
class chunked_output {
public:
    chunked_output(const std::optional<std::string>& path, std::ostream& out) : out_(out) {
        if (path) file_.emplace(*path);
        text_.reserve(chunk + chunk / 4);
    }
    chunked_output(const chunked_output&) = delete;
    chunked_output& operator=(const chunked_output&) = delete;
    ~chunked_output() {
        if (writing_.valid()) writing_.wait();  // an error elsewhere: let the write end before the file goes
    }
    std::string& text() noexcept { return text_; }
    void maybe_flush() {
        if (text_.size() < chunk) return;
        wait();
        std::swap(text_, spare_);
        text_.clear();
        writing_ = std::async(std::launch::async, [this] { write(spare_); });
    }
    void finish() {
        wait();
        write(text_);
        if (file_) file_->commit();
    }

private:
    static constexpr std::size_t chunk = std::size_t{1} << 20;
    void wait() {
        if (writing_.valid()) writing_.get();  // rethrows a write error
    }
    void write(const std::string& text) {
        if (file_) {
            file_->write(text);
        } else {
            out_.write(text.data(), static_cast<std::streamsize>(text.size()));
            out_.flush();
            if (!out_) throw error("cannot write to standard output");
        }
    }

    std::ostream& out_;
    std::optional<output_file> file_;
    std::string text_, spare_;
    std::future<void> writing_;
};

sample key_row(const key& k) { return sample{k.time, k.frame, k.rotation, k.translation, k.has_time}; }

/// Rows are formatted on a second thread (for large outputs; small ones,
/// where starting it costs more than it saves, inline): the caller, reading
/// and resampling, hands over batches of rows in order; a bounded queue
/// keeps memory constant. Errors of the formatting thread come back from
/// the next call, or from finish().
class row_pipeline {
public:
    row_pipeline(table_writer& writer, chunked_output& out, bool threaded) : writer_(writer), out_(out) {
        if (!threaded) return;
        batch_.rows.reserve(batch_rows);
        thread_ = std::thread([this] { consume(); });
    }
    row_pipeline(const row_pipeline&) = delete;
    row_pipeline& operator=(const row_pipeline&) = delete;
    ~row_pipeline() {
        if (thread_.joinable()) {
            stop();
            thread_.join();
        }
    }
    void begin_track(const std::string& name, bool translation) {
        if (!thread_.joinable()) return writer_.begin_track(name, translation);
        batch_.begins.push_back({batch_.rows.size(), name, translation});
    }
    void row(const sample& s) {
        if (!thread_.joinable()) {
            writer_.row(s);
            out_.maybe_flush();
            return;
        }
        batch_.rows.push_back(s);
        if (batch_.rows.size() == batch_rows) hand_over();
    }
    void finish() {
        if (!thread_.joinable()) return;
        hand_over();
        stop();
        thread_.join();
        if (failure_) std::rethrow_exception(failure_);
    }

private:
    static constexpr std::size_t batch_rows = 4096, max_batches = 4;
    struct track_begin {
        std::size_t before_row;
        std::string name;
        bool translation;
    };
    struct batch {
        std::vector<sample> rows;
        std::vector<track_begin> begins;
    };

    void hand_over() {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [this] { return queue_.size() < max_batches || failure_; });
        if (failure_) std::rethrow_exception(failure_);
        queue_.push_back(std::move(batch_));
        batch_ = batch{};
        batch_.rows.reserve(batch_rows);
        changed_.notify_all();
    }
    void stop() {
        const std::lock_guard lock(mutex_);
        done_ = true;
        changed_.notify_all();
    }
    void consume() {
        try {
            for (;;) {
                batch b;
                {
                    std::unique_lock lock(mutex_);
                    changed_.wait(lock, [this] { return !queue_.empty() || done_; });
                    if (queue_.empty()) return;
                    b = std::move(queue_.front());
                    queue_.pop_front();
                    changed_.notify_all();
                }
                std::size_t next_begin = 0;
                for (std::size_t i = 0; i <= b.rows.size(); ++i) {
                    for (; next_begin < b.begins.size() && b.begins[next_begin].before_row == i; ++next_begin)
                        writer_.begin_track(b.begins[next_begin].name, b.begins[next_begin].translation);
                    if (i == b.rows.size()) break;
                    writer_.row(b.rows[i]);
                    out_.maybe_flush();
                }
            }
        } catch (...) {
            const std::lock_guard lock(mutex_);
            failure_ = std::current_exception();
            changed_.notify_all();
        }
    }

    table_writer& writer_;
    chunked_output& out_;
    batch batch_;
    std::deque<batch> queue_;
    std::mutex mutex_;
    std::condition_variable changed_;
    bool done_ = false;
    std::exception_ptr failure_;
    std::thread thread_;  // started once everything else exists
};

/// Pass 2 over a line-based input whose tracks come one after another:
/// each track is resampled (or converted) as its keys arrive.
void stream_rows(const options& o, const input_source& src, format f, const document_facts& d, row_pipeline& writer,
                 warnings& warn) {
    const auto stream = src.open();
    const read_options ro = reading(o, src);
    const auto reader = make_key_reader(*stream, f, ro, warn);
    const auto row = [&](const sample& s) { writer.row(s); };
    std::optional<track_resampler> resampler;
    std::size_t track = 0;
    std::string name;
    raw_key raw;
    bool started = false;
    while (reader->next(name, raw)) {
        const key k = make_key(raw, ro.settings, warn);
        if (!started || name != d.tracks[track].name) {
            if (resampler) resampler->finish();
            track += started ? 1 : 0;
            started = true;
            const auto& facts = d.tracks[track];
            writer.begin_track(facts.name, facts.translation);
            if (o.cmd == command::resample) resampler.emplace(resampling(o), facts.euler, facts.translation, row);
        }
        if (resampler) resampler->add(k);
        else row(key_row(k));
    }
    if (resampler) resampler->finish();
}

/// The tracks of an input read whole.
void whole_rows(const options& o, const input& doc, row_pipeline& writer) {
    const auto row = [&](const sample& s) { writer.row(s); };
    for (const track& t : doc.tracks) {
        bool translation = false;
        for (const key& k : t.keys) translation = translation || k.translation.has_value();
        writer.begin_track(t.name, translation);
        if (o.cmd == command::resample) {
            resample(t, resampling(o), doc.source, row);
        } else {
            for (const key& k : t.keys) row(key_row(k));
        }
    }
}

/// resample or convert one input into `target` (a file) or `out`.
void transform(const options& o, const input_source& src, format in_fmt, format out_fmt,
               const std::optional<std::string>& target, std::ostream& out, warnings& warn) {
    // Line-based input streams in two passes: everything is validated before
    // the first byte is written, so an error never leaves partial output.
    bool interleaved = in_fmt == format::json;
    document_facts d;
    std::optional<input> whole;
    if (!interleaved) d = scan(o, src, in_fmt, warn, interleaved);
    if (interleaved) {
        whole = load(o, src, warn);
        d = facts_of(*whole);
    }
    d.check(o, src.source());
    const write_options wopts = output_settings(o, d.tracks.front().euler);
    chunked_output sink(target, out);
    const auto writer = make_writer(out_fmt, sink.text(), d.table(o), wopts, warn);
    {
        row_pipeline rows(*writer, sink, d.rows(o) > 20000);
        if (whole) whole_rows(o, *whole, rows);
        else stream_rows(o, src, in_fmt, d, rows, warn);
        rows.finish();
    }
    writer->finish();
    sink.finish();
}

/// resample or convert one input; errors and warnings to `err`. Returns the status.
int transform_one(const options& o, const std::string& name, std::istream& in, std::ostream& out, std::ostream& err) {
    try {
        if (name == "-" && o.output_dir) throw usage_error("standard input ('-') cannot be used with --output-dir");
        const input_source src(name, in);
        warnings warn(err, src.source());
        const format in_fmt = src.detect(o.from);
        std::optional<std::string> target;
        format out_fmt = o.to.value_or(in_fmt);
        if (o.output_dir) {
            std::filesystem::path file = std::filesystem::path(name).filename();
            file.replace_extension(to_string(out_fmt));
            target = (std::filesystem::path(*o.output_dir) / file).string();
        } else if (o.output && *o.output != "-") {
            target = *o.output;
            if (!o.to) out_fmt = format_of_path(*target).value_or(in_fmt);
        }
        transform(o, src, in_fmt, out_fmt, target, out, warn);
        return 0;
    } catch (const usage_error&) {
        throw;
    } catch (const error& e) {
        print_error(err, e.what());
        return 2;
    }
}

/// Several files into --output-dir, --jobs at a time. Each file's messages
/// are kept and printed in input order, so the output does not depend on
/// which job finished first.
int transform_batch(const options& o, const std::vector<std::string>& inputs, std::istream& in, std::ostream& out,
                    std::ostream& err) {
    std::vector<std::string> messages(inputs.size());
    std::vector<int> statuses(inputs.size(), 0);
    std::exception_ptr usage;  // a bad flag stops everything, as for one file
    std::atomic<std::size_t> next{0}, done{0};
    std::mutex progress_mutex;
    const auto work = [&] {
        for (std::size_t i; (i = next++) < inputs.size();) {
            std::ostringstream messages_of_file;
            try {
                statuses[i] = transform_one(o, inputs[i], in, out, messages_of_file);
            } catch (...) {
                const std::lock_guard lock(progress_mutex);
                if (!usage) usage = std::current_exception();
                next = inputs.size();
            }
            messages[i] = messages_of_file.str();
            const std::size_t finished = ++done;
            if (o.progress) {
                const std::lock_guard lock(progress_mutex);
                err << fmt::format("\rkeyrot: {}/{} files", finished, inputs.size()) << std::flush;
            }
        }
    };
    const unsigned jobs = o.jobs ? o.jobs : std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::thread> workers;
    for (unsigned j = 1; j < std::min<std::size_t>(jobs, inputs.size()); ++j) workers.emplace_back(work);
    work();
    for (auto& w : workers) w.join();
    if (o.progress) err << '\n';
    if (usage) std::rethrow_exception(usage);
    int status = 0;
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        err << messages[i];
        status = std::max(status, statuses[i]);
    }
    return status;
}

int run_transform(const options& o, std::istream& in, std::ostream& out, std::ostream& err) {
    const std::vector<std::string> inputs = o.inputs.empty() ? std::vector<std::string>{"-"} : o.inputs;
    if (inputs.size() > 1 && !o.output_dir) throw usage_error("several input files need --output-dir DIR");
    if (o.output_dir && o.output) throw usage_error("-o and --output-dir: expected one of them");
    if (o.output_dir) {
        std::error_code ec;
        std::filesystem::create_directories(*o.output_dir, ec);
        if (ec) throw error(fmt::format("cannot create directory '{}': {}", *o.output_dir, ec.message()));
    }
    if (inputs.size() == 1) return transform_one(o, inputs.front(), in, out, err);
    return transform_batch(o, inputs, in, out, err);
}

/// Writes `text` to -o FILE (atomically) or to `out`.
void emit(const options& o, const std::string& text, std::ostream& out) {
    if (o.output && *o.output != "-") write_file_atomically(*o.output, text);
    else out << text << std::flush;
}

// ---------------------------------------------------------------- slerp

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
                                      what, to_string(o.from_rep), text));
    }
    if (o.from_rep == rep::quat) {
        const auto wxyz = from_quat_order({values[0], values[1], values[2], values[3]}, o.order);
        std::copy(wxyz.begin(), wxyz.end(), k.values.begin());
    } else {
        std::copy(values.begin(), values.end(), k.values.begin());
    }
    return k;
}

int run_slerp(const options& o, std::ostream& out, std::ostream& err) {
    if (o.how == method::squad) throw usage_error("--method squad needs more than two keys: use resample");
    std::vector<double> ts = o.ts;
    if (o.steps) {
        if (*o.steps < 1) throw usage_error(fmt::format("--steps: expected at least 1, got {}", *o.steps));
        for (int i = 0; i <= *o.steps; ++i) ts.push_back(static_cast<double>(i) / *o.steps);
    }
    if (ts.empty()) throw usage_error("slerp needs -t T or --steps N");
    // Each operand is its own source for messages: "keyrot: Q1: quaternion is zero: ...".
    warnings warn0(err, "Q0"), warn1(err, "Q1");
    const track t{"", o.euler, {make_key(operand("Q0", o.q0, o, 0), settings_of(o), warn0),
                                make_key(operand("Q1", o.q1, o, 1), settings_of(o), warn1)}};
    const rotation_curve curve(t, o.how, o.way);
    table_info info;
    info.times = time_columns::time_only;
    info.time_name = "t";
    info.how = o.how;
    std::string text;
    const auto writer = make_writer(o.to.value_or(format::csv), text, info, output_settings(o, t.euler), warn0);
    writer->begin_track("", false);
    for (double h : ts) {
        const quat q = h == 0 ? curve.at_key(0) : h == 1 ? curve.at_key(1) : curve.at(0, h);
        writer->row(sample{h, std::nullopt, q, std::nullopt});
    }
    writer->finish();
    emit(o, text, out);
    return 0;
}

// ---------------------------------------------------------------- compare

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

int run_compare(const options& o, std::istream& in, std::ostream& out, std::ostream& err) {
    if (o.inputs.size() != 2) throw usage_error("compare needs two files: EXPECTED ACTUAL");
    if (o.inputs[0] == "-" && o.inputs[1] == "-") throw usage_error("compare: only one of EXPECTED and ACTUAL can be '-'");
    const input_source expected_src(o.inputs[0], in), actual_src(o.inputs[1], in);
    warnings warn_e(err, expected_src.source()), warn_a(err, actual_src.source());
    const input expected = load(o, expected_src, warn_e);
    const input actual = load(o, actual_src, warn_a);
    const tolerances tol{o.tol_deg, o.tol_translation};
    const comparison c = compare_tracks(expected.tracks, actual.tracks, tol);

    constexpr std::size_t max_reasons = 10;
    std::size_t told = 0;
    for (const row_difference& r : c.rows) {
        if (r.pass()) continue;
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
    std::string out = fmt::format("{}: {} track{}, {}\n", doc.source, infos.size(), infos.size() == 1 ? "" : "s",
                                  to_string(doc.fmt));
    for (const track_info& t : infos) {
        out += fmt::format("{}: {} key{}, {} s to {} s, given as {}\n", t.name.empty() ? "track" : "track " + t.name,
                           t.keys, t.keys == 1 ? "" : "s", num(t.start), num(t.end), rep_list(t.given_as));
        std::vector<std::size_t> long_way;
        for (std::size_t i = 0; i < t.segments.size(); ++i) {
            const segment_info& s = t.segments[i];
            if (i == 0) out += "  segment  angle (deg)  speed (deg/s)\n";
            out += fmt::format("  {:<7}  {:<11}  {}{}\n", fmt::format("{}-{}", i, i + 1), num(s.angle_deg),
                               num(s.speed_deg_s), s.direct_long_way ? "  (long way with --path direct)" : "");
            if (s.direct_long_way) long_way.push_back(i);
        }
        out += fmt::format("  keys flipped by --path shortest: {}\n", index_list(t.flipped));
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
                                           num(s.speed_deg_s), s.direct_long_way));
        out += fmt::format(
            "{}\n{{\"name\": {}, \"keys\": {}, \"start\": {}, \"end\": {}, \"given_as\": [{}], \"segments\": [{}], "
            "\"flipped\": {}, \"renormalised\": {}, \"near_gimbal_lock\": {}}}",
            n ? "," : "", json_quote(t.name), t.keys, num(t.start), num(t.end), fmt::join(reps, ", "),
            fmt::join(segments, ", "), list(t.flipped), list(t.renormalised), list(t.near_gimbal));
    }
    out += "]}\n";
    return out;
}

int run_info(const options& o, std::istream& in, std::ostream& out, std::ostream& err) {
    const std::vector<std::string> inputs = o.inputs.empty() ? std::vector<std::string>{"-"} : o.inputs;
    const bool as_json = o.to == format::json || o.to == format::ndjson;
    std::string text;
    int status = 0;
    for (const std::string& name : inputs) {
        try {
            const input_source src(name, in);
            warnings warn(err, src.source());
            const input doc = load(o, src, warn);
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

}  // namespace

int run(const options& o, std::istream& in, std::ostream& out, std::ostream& err) {
    switch (o.cmd) {
        case command::resample:
        case command::convert: return run_transform(o, in, out, err);
        case command::slerp: return run_slerp(o, out, err);
        case command::compare: return run_compare(o, in, out, err);
        case command::info: return run_info(o, in, out, err);
    }
    return 2;
}

}  // namespace keyrot
