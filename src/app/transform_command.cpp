// SPDX-License-Identifier: MIT
// resample, convert and reduce: an input streams in two passes (validate,
// then make the rows as the keys arrive, by the command's row_source), or
// in one into a file; interleaved tracks, and JSON documents the streaming
// reader declines, are read whole; a BVH take is read a joint at a time.
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <filesystem>
#include <mutex>
#include <new>
#include <ostream>
#include <set>
#include <sstream>
#include <thread>
#include <utility>

#include "app/commands.hpp"
#include "app/output_names.hpp"
#include "app/plan.hpp"
#include "app/plots.hpp"
#include "app/row_sources.hpp"
#include "app/track_rows.hpp"
#include "ground/held_warnings.hpp"
#include "ground/thread_start.hpp"
#include "io/bvh/bvh_read.hpp"
#include "io/common/output.hpp"
#include "io/document.hpp"
#include "io/gltf/gltf_read.hpp"
#include "io/open.hpp"
#include "keyrot/reduce.hpp"

namespace keyrot::detail {
namespace {

/// One input's resample, convert or reduce, settled before it is read.
struct transform_plan {
    const options& flags;  // for the output settings, which wait for the input's Euler sequence
    read_options reading;
    std::unique_ptr<row_source> rows;
    format in = format::csv, out = format::csv;
    std::optional<std::string> target;  // the output file; none for standard output
    durable_batch* batch = nullptr;     // --fsync in a batch: what puts the output file in place
    // A glTF input as its first pass loaded it, for the passes after and a
    // glTF output that rewrites it: the file is read once (loaded_gltf).
    mutable std::shared_ptr<gltf_source> gltf;
};

/// The plan's glTF input, loaded on first use.
std::shared_ptr<gltf_source> loaded_gltf(const transform_plan& p, const input_source& src, warnings& warn) {
    if (!p.gltf) p.gltf = read_gltf_source(*src.open(), p.in, p.reading, warn);
    return p.gltf;
}

/// The keys of one pass over the input, and the stream they are read from
/// (none for glTF, which is read from memory after its first pass).
struct pass_keys {
    std::unique_ptr<std::istream> stream;
    std::unique_ptr<key_reader> reader;
};

pass_keys open_keys(const transform_plan& p, const input_source& src, warnings& warn,
                    std::function<bool()> parse_ahead = nullptr) {
    if (is_gltf(p.in)) return {nullptr, make_gltf_reader(loaded_gltf(p, src, warn), p.reading, warn)};
    pass_keys keys{src.open(), nullptr};
    keys.reader = make_key_reader(*keys.stream, p.in, p.reading, warn, std::move(parse_ahead));
    return keys;
}

/// The plan's output, and the values of their own its rows carry.
struct written_output {
    std::unique_ptr<table_output> table;
    own_values own;
};

/// The plan's output for an input of facts `d` (the writer's warnings to
/// `output_warn`): a glTF output of a glTF input rewrites that file.
written_output open_output(const transform_plan& p, const input_source& src, const document_facts& d,
                           std::ostream& out, warnings& warn, warnings& output_warn) {
    write_options w = writing(p.flags, d.tracks.front().euler);
    w.commit.batch = p.batch;
    w.commit.follow_links = !p.flags.output_dir;
    if (is_gltf(p.out) && is_gltf(p.in)) w.gltf = loaded_gltf(p, src, warn);
    // A BVH output of a BVH input keeps its hierarchy; a glTF output makes it the nodes.
    if ((p.out == format::bvh || is_gltf(p.out)) && p.in == format::bvh) w.bvh = read_bvh_source(*src.open(), p.reading);
    return {open_table(p.out, p.target, out, p.rows->table(d), w, output_warn), own_values(w, p.out)};
}

/// Pass 1 over a streamed input: every key validated, the facts learnt.
/// Stops early (read_whole = true) when a track comes back after another
/// one began, or when the reader declines the document (a JSON document
/// the streaming reader does not take): such input is then read whole.
document_facts scan(const transform_plan& p, const input_source& src, warnings& warn, bool& read_whole) {
    const pass_keys keys = open_keys(p, src, warn, [] { return true; });
    key_reader* const reader = keys.reader.get();
    document_facts d;
    std::set<std::string> seen;
    std::string name;
    raw_key raw;
    read_whole = false;
    while (reader->next(name, raw)) {
        key k = make_key(raw, reader->settings(), warn);
        const bool same_track = d.on_last_track(name);
        if (same_track) {
            check_next(d.tracks.back().last, k, src.source());
        } else if (!seen.insert(name).second) {
            read_whole = true;
            return d;
        }
        d.add(name, reader->settings(), std::move(k), same_track);
    }
    read_whole = reader->declined();
    if (read_whole) return d;
    if (d.tracks.empty()) throw input_error(where(src.source(), reader->start()), "no keys: expected at least one key");
    d.named = reader->named();
    return d;
}

/// Pass 1 over a JSON document, where the streaming reader takes it. False
/// when it declines the document, or meets an error there: the document is
/// then read whole, which says what is wrong as read_json does (syntax
/// anywhere before content). Its warnings are held back until it is known
/// which.
bool scan_json(const transform_plan& p, const input_source& src, document_facts& d, warnings& warn) {
    return with_held_warnings(warn, [&](warnings& attempt) {
        bool read_whole = false;
        d = scan(p, src, attempt, read_whole);
        return !read_whole;
    });
}

/// Pass 2 over a streamed input whose tracks come one after another:
/// stream_keys, parsing ahead where it pays.
std::optional<document_facts> stream_rows(const transform_plan& p, const input_source& src,
                                          const document_facts* known, const written_output& rows, warnings& warn) {
    row_counts counts;
    // Parsing ahead on a thread of its own pays when keys outnumber rows
    // (motion capture at 120 Hz resampled to 24 fps, say). Otherwise the
    // formatting threads keep the cores busy, and it would only cost.
    const pass_keys input = open_keys(p, src, warn, [&] { return counts.rows < counts.keys; });
    return stream_keys(*input.reader, *p.rows, *rows.table, rows.own, counts, known, src.source(), warn);
}

/// One pass over a glTF input by rows_apart, where it takes it (a glTF file
/// resampled into a glTF file) and it pays: a thread costs about what a
/// few thousand keys do, and a quarter of a megabyte of buffers holds more.
std::optional<document_facts> rows_by_track(const transform_plan& p, const input_source& src,
                                            const written_output& rows, warnings& warn) {
    if (!is_gltf(p.in)) return std::nullopt;
    const std::shared_ptr<gltf_source> loaded = loaded_gltf(p, src, warn);
    const auto readers = [&] {
        if (read_buffers(*loaded) < 256 * 1024) return std::vector<std::unique_ptr<key_reader>>{};
        return make_gltf_track_readers(loaded, p.reading);
    };
    return rows_apart(readers, *p.rows, *rows.table, rows.own, src.source());
}

/// Every track's keys to the row source's check_track: an input read whole
/// (`doc`), or streamed once more (only where some track has a check).
void check_tracks(const transform_plan& p, const input_source& src, const std::optional<document>& doc, warnings& warn) {
    if (doc) {
        for (const track& t : doc->tracks)
            if (const auto check = p.rows->check_track(t.name)) {
                for (const key& k : t.keys) check->add(k);
                check->finish();
            }
        return;
    }
    if (!p.rows->checks_tracks()) return;
    const pass_keys keys = open_keys(p, src, warn);
    std::string name, track;
    raw_key raw;
    std::unique_ptr<row_source::track_check> check;
    while (keys.reader->next(name, raw)) {
        if (!check || name != track) {
            if (check) check->finish();
            check = p.rows->check_track(name), track = name;
        }
        check->add(make_key(raw, keys.reader->settings(), warn));
    }
    if (check) check->finish();
}

/// The tracks of an input read whole, whose facts are `d`.
void whole_rows(const transform_plan& p, const document& doc, const document_facts& d, const written_output& out) {
    std::size_t rows_put = 0;
    own_values own = out.own;
    table_output& rows = *out.table;
    const row_sink row(rows, rows_put, &own);
    for (std::size_t i = 0; i < doc.tracks.size(); ++i) {
        const track& t = doc.tracks[i];
        const channels carried = d.tracks[i].carried;
        rows.begin_track(t.name, carried, p.rows->written(t.interpolation));
        p.rows->begin_track(t.name, t.euler, t.interpolation, carried, row);
        for (const key& k : t.keys) p.rows->add(k);
        p.rows->end_track();
    }
}

/// resample, convert or reduce from streamed input into the plan's file in one
/// pass. The writer needs facts before the first row that pass 1 would
/// gather (track names, channels, convert's time columns); they are
/// guessed from the first key instead. When a guess proves wrong, the
/// reader declines the document, or anything fails, the temporary file is
/// dropped and false returned: the two passes then give the output or the
/// error they always give. Warnings are held back until it is known which;
/// the output's (gimbal lock) come after the input's, as the two passes
/// give them.
bool transform_in_one_pass(const transform_plan& p, const input_source& src, std::ostream& out, warnings& warn) {
    return with_held_warnings(warn, [&](warnings& attempt) {
        std::ostringstream output_held;
        warnings output_warn(output_held, src.source());
        document_facts guess;
        {
            const pass_keys keys = open_keys(p, src, attempt);
            key_reader* const reader = keys.reader.get();
            std::string name;
            raw_key raw;
            if (!reader->next(name, raw)) return false;
            guess.add(name, reader->settings(), make_key(raw, reader->settings(), attempt));
            guess.named = reader->named();
        }
        const written_output output = open_output(p, src, guess, out, attempt, output_warn);
        std::optional<document_facts> seen = rows_by_track(p, src, output, attempt);
        if (!seen) seen = stream_rows(p, src, nullptr, output, attempt);
        if (!seen || p.rows->table(*seen) != p.rows->table(guess)) return false;
        p.rows->check(*seen, attempt);
        for (const auto& t : seen->tracks)
            if (t.carried != channels_of(t.first)) return false;
        output.table->finish();
        attempt.adopt(output_warn, output_held.str());
        return true;
    });
}

/// resample, convert or reduce one input into the plan's file or `out`.
void transform(const transform_plan& p, const input_source& src, std::ostream& out, std::ostream& err) {
    warnings warn(err, src.source());
    // One pass where an error on the way leaves nothing written: into a file
    // that replaces its target at the end, a table written at its end, or
    // standard output redirected to a file, cut back after a failure.
    std::optional<standard_output_mark> mark;
    if (!p.target && !written_at_finish(p.out) && !src.is_standard_output()) mark = standard_output_mark::of(out);
    const bool one_pass = (p.target && replaced_on_commit(*p.target)) || written_at_finish(p.out) || mark;
    if (one_pass && transform_in_one_pass(p, src, out, warn)) return p.rows->report(out, err);
    if (mark) mark->take_back(out);
    p.rows->restart();
    // Otherwise everything is validated before the first byte is written,
    // so that an error never leaves partial output (on standard output, or
    // in a pipe or device named by -o).
    bool read_whole = false;
    document_facts d;
    std::optional<document> whole;
    if (p.in == format::json) read_whole = !scan_json(p, src, d, warn);
    else d = scan(p, src, warn, read_whole);
    if (read_whole) {
        whole = read_document(*src.open(), p.in, p.reading, warn);
        d = facts_of(*whole);
    }
    p.rows->check(d, warn);
    check_tracks(p, src, whole, warn);
    const written_output output = open_output(p, src, d, out, warn, warn);
    if (whole) whole_rows(p, *whole, d, output);
    else if (!stream_rows(p, src, &d, output, warn))  // pass 1 took it: the document is not what it was
        throw error(changed_while_read(src.source()));
    output.table->finish();
    p.rows->report(out, err);
}

/// What the options make of input `name`: how it is read, its row source
/// (reduce's told to `watch`, where there is one), the formats, where its output goes.
transform_plan plan_for(const options& o, const std::string& name, const input_source& src, durable_batch* batch,
                        reduction_observer* watch) {
    transform_plan p{o, reading(o, src.source()), nullptr, src.detect(o.from), format::csv, std::nullopt, batch, nullptr};
    p.out = o.to.value_or(p.in);
    if (o.output_dir) p.target = in_output_dir(*o.output_dir, name, p.out).string();
    else if ((p.target = output_path(o)) && !o.to) p.out = format_of_path(*p.target).value_or(p.in);
    check_output_format(o, p.out, p.target);
    if (o.cmd == command::resample) {
        if ((o.velocity || o.acceleration) && (p.out == format::bvh || is_gltf(p.out)))
            throw usage_error(fmt::format("--{}: {} has no place for an angular velocity: expected --to csv, json or "
                                          "ndjson, or -o with one of their extensions",
                                          o.velocity ? "velocity" : "acceleration", p.out == format::bvh ? "BVH" : "glTF"));
        p.rows = make_frame_rows(resampling(o), o.how.has_value(), src.source());
    } else if (o.cmd == command::reduce) {
        if (p.out == format::bvh)
            throw usage_error("reduce: BVH has a line for every frame, so it cannot drop keys: expected --to csv, "
                              "json, ndjson, gltf or glb, or -o with one of their extensions");
        p.rows = make_reduced_rows(reducing(o), o.how.has_value(), o.report == format::json, src.source(),
                                   is_gltf(p.out), watch);
    } else {
        p.rows = make_key_rows();
    }
    return p;
}

/// resample, convert or reduce one input; errors and warnings to `err`.
/// With `batch`, its output file is put in place by the batch; with
/// `watch`, reduce tells it what it keeps. Returns the status.
int transform_one(const options& o, const std::string& name, std::istream& in, std::ostream& out, std::ostream& err,
                  durable_batch* batch, reduction_observer* watch) {
    try {
        if (is_standard_stream(name) && o.output_dir)
            throw usage_error("standard input ('-') cannot be used with --output-dir");
        const input_source src(name, in);
        transform(plan_for(o, name, src, batch, watch), src, out, err);
        return 0;
    } catch (const option_error&) {  // the whole run's
        throw;
    } catch (const error& e) {
        print_error(err, e.what());
        return 2;
    } catch (const std::bad_alloc&) {  // e.g. a CSV line of gigabytes
        print_error(err, source_name(name) + ": out of memory");
        return 2;
    }
}

/// Several files into --output-dir, --jobs at a time. Each file's messages
/// are kept and printed in input order, so the output does not depend on
/// which job finished first. With --fsync, the files are made durable
/// together at the end (durable_batch): the disk is waited for once, not
/// once a file.
int transform_batch(const options& o, const std::vector<std::string>& inputs, std::istream& in, std::ostream& out,
                    std::ostream& err, std::vector<reduction_plot>& drawn) {
    std::vector<std::string> messages(inputs.size()), reports(inputs.size());  // reduce --report json
    std::vector<int> statuses(inputs.size(), 0);
    std::exception_ptr stop;  // a bad flag (or no memory left) stops everything, as for one file
    std::atomic<std::size_t> next{0}, done{0};
    std::mutex progress_mutex;
    std::optional<durable_batch> batch;
    if (o.fsync) batch.emplace();
    const auto work = [&] {
        for (std::size_t i; (i = next++) < inputs.size();) {
            try {
                std::ostringstream messages_of_file, report_of_file;  // (the outputs go to files)
                statuses[i] = transform_one(o, inputs[i], in, report_of_file, messages_of_file, batch ? &*batch : nullptr,
                                            drawn.empty() ? nullptr : &drawn[i]);
                messages[i] = messages_of_file.str();
                reports[i] = report_of_file.str();
                const std::size_t finished = ++done;
                if (o.progress) {
                    const std::lock_guard lock(progress_mutex);
                    err << fmt::format("\rkeyrot: {}/{} files", finished, inputs.size()) << std::flush;
                }
            } catch (...) {
                const std::lock_guard lock(progress_mutex);
                if (!stop) stop = std::current_exception();
                next = inputs.size();
            }
        }
    };
    const unsigned jobs = o.jobs ? o.jobs : std::max(1u, std::thread::hardware_concurrency());
    const std::size_t threads = std::min<std::size_t>(jobs, inputs.size());
    std::vector<std::thread> workers;
    workers.reserve(threads);
    for (std::size_t j = 1; j < threads; ++j) {
        std::thread t;
        if (!try_start_thread(t, work)) break;  // fewer jobs
        workers.push_back(std::move(t));
    }
    work();
    for (auto& w : workers) w.join();
    if (o.progress) err << '\n';
    if (stop) std::rethrow_exception(stop);
    int status = 0;
    std::size_t failed = 0;
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        err << messages[i];
        out << reports[i];
        status = std::max(status, statuses[i]);
        failed += statuses[i] != 0;
    }
    say_failed_files(err, failed, inputs.size());
    if (batch) {
        try {
            batch->finish();
        } catch (const error& e) {
            print_error(err, e.what());
            status = 2;
        }
    }
    return status;
}

}  // namespace

int run_transform(const options& o, std::istream& in, std::ostream& out, std::ostream& err) {
    const std::vector<std::string> inputs = input_names(o);
    if (inputs.size() > 1 && !o.output_dir) throw usage_error("several input files need --output-dir DIR");
    if (o.output_dir && o.output) throw usage_error("-o and --output-dir: expected one of them");
    if (o.output_dir) {
        check_output_names(o, inputs);
        std::error_code ec;
        std::filesystem::create_directories(*o.output_dir, ec);
        if (ec) throw error(fmt::format("cannot create directory '{}': {}", *o.output_dir, ec.message()));
    }
    // reduce --plot: the picture's file opened first (a target that cannot be
    // written is said at once), each input's tracks drawn as it is reduced,
    // and the picture written when every input is.
    std::optional<picture_file> picture;
    std::vector<reduction_plot> drawn;
    if (o.plot) {
        picture.emplace(*o.plot, o.fsync, out);
        drawn.reserve(inputs.size());
        for (const std::string& name : inputs) drawn.emplace_back(o, printable(source_name(name)), inputs.size() > 1);
    }
    const int status = inputs.size() == 1
                           ? transform_one(o, inputs.front(), in, out, err, nullptr, drawn.empty() ? nullptr : &drawn[0])
                           : transform_batch(o, inputs, in, out, err, drawn);
    if (picture && status == 0) {
        svg::figure f;
        for (const reduction_plot& d : drawn) f.panels.insert(f.panels.end(), d.panels().begin(), d.panels().end());
        picture->write(f);
    }
    return status;
}

}  // namespace keyrot::detail
