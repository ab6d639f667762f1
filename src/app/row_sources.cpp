// SPDX-License-Identifier: MIT
#include "app/row_sources.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <ostream>
#include <utility>

#include "app/usage_error.hpp"
#include "io/common/output.hpp"
#include "io/json/json_object.hpp"

namespace keyrot::detail {

document_facts facts_of(const document& doc) {
    document_facts d;
    d.named = doc.named;
    for (const track& t : doc.tracks) {
        key_settings s;
        s.euler = t.euler;
        s.key_fps = t.key_fps;
        s.interpolation = t.interpolation;
        for (const key& k : t.keys) d.add(t.name, s, key(k));
    }
    return d;
}

namespace {

/// The methods a file states for a track (`own`) into resample's or reduce's options `r`.
template <class Options>
void own_methods(const track_interpolation& own, Options& r) {
    r.how = own.rotation, r.translation_how = own.translation, r.scale_how = own.scale, r.weights_how = own.weights;
}

table_row key_row(const key& k) {
    return table_row{{k.time, k.frame, k.rotation, k.translation, k.scale, k.weights,  // (views k's)
                      k.rates.get()},
                     nullptr,
                     k.spline.get()};
}

/// A glTF sampler's method for channel values played by `m`: STEP where
/// they are held, LINEAR (slerp for a rotation) for any other.
method linear_or_step(method m) { return m == method::step ? method::step : method::slerp; }

/// check_frame_range, its frame limit said as the flag that raises it:
/// "... expected at most 240 (--max-frames N raises the limit)".
void check_frames(const key& first, const key& last, const std::string& track_name, const resample_options& opts,
                  const std::string& source) {
    try {
        check_frame_range(first, last, track_name, opts, source);
    } catch (const frame_limit_error& e) {
        throw error(std::string(e.what()) + " (--max-frames N raises the limit)");
    }
}

/// resample: every frame of the grid within a track's keys.
class frame_rows final : public row_source {
public:
    /// `method_given`: --method overrides the interpolation a file states; `source` names the input.
    frame_rows(const resample_options& r, bool method_given, std::string source)
        : opts_(r), method_given_(method_given), source_(std::move(source)) {}
    table_info table(const document_facts& d) const override {
        table_info info;
        info.named = d.named;
        info.carried = d.carried();
        info.fps = opts_.fps;
        info.velocity = opts_.velocity, info.acceleration = opts_.acceleration;
        // The method, when one interpolates every track's rotation.
        const method first = of(d.tracks.front().interpolation).how;
        if (std::all_of(d.tracks.begin(), d.tracks.end(), [&](const auto& t) { return of(t.interpolation).how == first; }))
            info.method = to_string(first);
        return info;
    }
    /// The frame grid of every track is within bounds. Frame numbers
    /// count at 24 fps unless stated, whatever --fps is: said where that
    /// could surprise.
    void check(const document_facts& d, warnings& warn) const override {
        for (const auto& t : d.tracks) {
            check_method(of(t.interpolation).how, t.euler);
            if (of(t.interpolation).how == method::cubic && t.keys < 2)
                throw input_error(where(warn.source(), t.first.at),
                                  fmt::format("{}one key: --method cubic needs two keys or more",
                                              t.name.empty() ? "" : fmt::format("track '{}' has ", t.name)));
            check_frames(t.first, t.last, t.name, of(t.interpolation), warn.source());
        }
        if (d.velocity || d.acceleration)
            warn.once("rates", "ignoring the angular velocity and acceleration read: resample --velocity and "
                               "--acceleration give the resampled curve's own");
        const bool assumed = std::any_of(d.tracks.begin(), d.tracks.end(), [](const auto& t) { return !t.key_fps; });
        if (d.counted && assumed && opts_.fps != default_key_fps)
            warn.once("key rate", fmt::format("frame numbers count at {} fps (the default, whatever --fps is): "
                                              "--key-fps RATE reads them at another",
                                              default_key_fps));
    }
    /// Before the key's frames: never hours of output.
    void check_key(const key& first, const key& k, const std::string& name, const std::string& source) const override {
        // Far from both bounds, as nearly every key is, the frames need not be
        // worked out: a frame or two of margin covers the grid's tolerance.
        // (The first key was checked as a key of its own.)
        const double frames = (k.time - first.time) * opts_.fps;
        if (std::fabs(k.time * opts_.fps) < 0x1p52 && frames + 2 < opts_.max_frames) return;
        check_frames(first, k, name, opts_, source);
    }
    /// Frames are LINEAR (dense enough for any method), or STEP where they are held.
    track_interpolation written(const std::optional<track_interpolation>& own) const override {
        const resample_options r = of(own);
        return {linear_or_step(r.how), linear_or_step(r.translation_how.value_or(r.how)),
                linear_or_step(r.scale_how.value_or(r.how)), linear_or_step(r.weights_how.value_or(r.how))};
    }
    void begin_track(const std::string& name, const std::optional<euler_seq>& euler,
                     const std::optional<track_interpolation>& own, channels carried, row_sink row) override {
        row_.emplace(row);
        const resample_options r = of(own);
        row_->begin_track(euler, r.how, r.fps);
        resampler_.emplace(r, euler, carried, [this](const sample& s) { row_->frame(s); }, row_->arc_frames());
        track_ = name;
        first_.reset();
    }
    void add(const key& k) override {
        if (!first_) first_ = k.at;
        row_->key(k);
        resampler_->add(k);
    }
    void end_track() override {
        try {
            resampler_->finish();
        } catch (const spline_error& e) {
            throw unsettled(track_, first_.value_or(location{}), e);
        }
    }
    /// A cubic spline is solved as its keys come: to standard output, once before the first row.
    std::unique_ptr<track_check> check_track(const std::string& name) const override {
        if (!checks_tracks()) return nullptr;
        return std::make_unique<spline_check>(*this, name);
    }
    bool checks_tracks() const override { return method_given_ && opts_.how == method::cubic; }
    std::unique_ptr<row_source> for_track_apart() const override {
        return std::make_unique<frame_rows>(opts_, method_given_, source_);
    }

private:
    input_error unsettled(const std::string& track, const location& first, const spline_error& e) const {
        return input_error(where(source_, first),
                           fmt::format("{}{}", track.empty() ? "" : fmt::format("track '{}': ", track), e.what()));
    }
    class spline_check final : public track_check {
    public:
        spline_check(const frame_rows& rows, std::string name) : rows_(rows), name_(std::move(name)) {}
        void add(const key& k) override {
            if (!first_) first_ = k.at;
            builder_.add(k);
            drain(false);
        }
        void finish() override { drain(true); }

    private:
        void drain(bool end) {
            try {
                segment s;
                while (builder_.pop(s, end)) {
                }
            } catch (const spline_error& e) {
                throw rows_.unsettled(name_, first_.value_or(location{}), e);
            }
        }
        const frame_rows& rows_;
        std::string name_;
        std::optional<location> first_;
        segment_builder builder_{method::cubic, path::shortest, std::nullopt};
    };
    /// How a track whose file states `own` is resampled.
    resample_options of(const std::optional<track_interpolation>& own) const {
        resample_options r = opts_;
        if (!own) return r;
        r.time_rounding = own->time_rounding;
        if (!method_given_) own_methods(*own, r);
        return r;
    }

    resample_options opts_;
    bool method_given_;
    std::string source_;
    std::optional<row_sink> row_;
    std::optional<track_resampler> resampler_;
    std::string track_;
    std::optional<location> first_;  // the track's first key, which a spline_error names
};

/// convert: each key as it is, with its own frame or time.
class key_rows : public row_source {
public:
    table_info table(const document_facts& d) const override {
        table_info info;
        info.named = d.named;
        info.carried = d.carried();
        info.times = time_columns::as_given;
        info.any_frame = d.any_frame;
        info.velocity = d.velocity, info.acceleration = d.acceleration;
        info.rows_name = d.frames ? "frames" : "keys";
        // The rate frames count at, where the input states one for every track (an assumed one is not
        // written as if stated). Rows carry their times all the same: no reader needs it.
        const auto& first = d.tracks.front().key_fps;
        if (d.any_frame && std::all_of(d.tracks.begin(), d.tracks.end(), [&](const auto& t) { return t.key_fps == first; }))
            info.fps = first;
        return info;
    }
    void check(const document_facts&, warnings&) const override {}
    void check_key(const key&, const key&, const std::string&, const std::string&) const override {}
    /// The keys as the file interpolates them (LINEAR for a file that does not say).
    track_interpolation written(const std::optional<track_interpolation>& own) const override {
        return own.value_or(track_interpolation{});  // (its time_rounding is not written)
    }
    void begin_track(const std::string&, const std::optional<euler_seq>& euler, const std::optional<track_interpolation>&,
                     channels, row_sink row) override {
        row_ = row;
        row_->begin_track(euler, method::step, std::nullopt);  // (a row a key: how they play is not asked)
    }
    void add(const key& k) override {
        row_->key(k);
        row_->row(key_row(k));
    }
    void end_track() override {}

protected:
    std::optional<row_sink> row_;
};

/// reduce: the fewest of each track's keys that replay within tolerance
/// (track_reducer), as convert writes keys.
class reduced_rows final : public key_rows {
public:
    /// `method_given`: --method overrides the interpolation a file states.
    /// `gltf`: the output is a glTF file, which plays rotations LINEAR (slerp) or STEP only.
    reduced_rows(const reduce_options& r, bool method_given, bool report_json, std::string source, bool gltf,
                 reduction_observer* watch)
        : opts_(r), method_given_(method_given), report_json_(report_json), source_(std::move(source)), gltf_(gltf),
          watch_(watch) {}
    void check(const document_facts& d, warnings& warn) const override {
        key_rows::check(d, warn);
        for (const auto& t : d.tracks) {
            const reduce_options r = of(t.interpolation);
            check_method(r.how, t.euler);
            if (r.how == method::cubicspline || r.translation_how == method::cubicspline ||
                r.scale_how == method::cubicspline || r.weights_how == method::cubicspline)
                throw input_error(warn.source(),
                                  fmt::format("track '{}' is CUBICSPLINE: expected LINEAR or STEP keys, which reduce "
                                              "keeps as they are (resample it first, or give --method)",
                                              t.name));
            if (gltf_ && r.how != method::slerp && r.how != method::step)
                throw usage_error(fmt::format("--method {}: a glTF file plays its keys as slerp (LINEAR) or step "
                                              "(STEP): expected one of them, or another output format",
                                              to_string(r.how)));
        }
    }
    /// glTF plays the kept keys LINEAR (slerp; translations linear) or STEP.
    track_interpolation written(const std::optional<track_interpolation>& own) const override {
        const reduce_options r = of(own);
        return {r.how, linear_or_step(r.translation_how.value_or(r.how)), linear_or_step(r.scale_how.value_or(r.how)),
                linear_or_step(r.weights_how.value_or(r.how))};
    }
    void begin_track(const std::string& name, const std::optional<euler_seq>& euler,
                     const std::optional<track_interpolation>& own, channels carried, row_sink row) override {
        key_rows::begin_track(name, euler, own, carried, row);
        name_ = name;
        if (watch_) watch_->begin_track(name, euler, of(own));
        // A kept key goes out as it came in: a quaternion as given, not normalised.
        reducer_.emplace(of(own), euler, source_, [this](const key& k) {
            if (watch_) watch_->keep(k);
            table_row kept = key_row(k);
            if (k.given_as == rep::quat && k.given) {
                const auto& v = k.given->values;
                kept.rotation = quat{v[0], v[1], v[2], v[3]};
            }
            row_->key(k);
            row_->row(kept);
        });
    }
    void add(const key& k) override {
        if (watch_) watch_->add(k);
        reducer_->add(k);
    }
    void end_track() override {
        reducer_->finish();
        summaries_.emplace_back(name_, reducer_->summary());
        if (watch_) watch_->end_track();
    }
    void restart() override {
        summaries_.clear();
        if (watch_) watch_->restart();
    }
    /// A line per track on `err`; with --report json, a JSON report on `out` instead.
    void report(std::ostream& out, std::ostream& err) const override {
        if (report_json_) return write_to_stream(out, json_report());
        std::string text;
        for (const auto& [name, s] : summaries_)
            text += fmt::format("keyrot: {}{}: {} keys -> {}, largest error {:.6g} deg{}\n", source_,
                                name.empty() ? "" : fmt::format(" track '{}'", name), s.keys, s.kept, s.worst_deg,
                                s.worst_translation > 0 ? fmt::format(", {:.6g} in translation", s.worst_translation)
                                                        : "");
        err << text << std::flush;
    }

private:
    /// How a track whose file states `own` is reduced.
    reduce_options of(const std::optional<track_interpolation>& own) const {
        reduce_options r = opts_;
        if (own && !method_given_) own_methods(*own, r);
        return r;
    }
    std::string json_report() const {
        std::size_t keys = 0, kept = 0;
        std::vector<std::string> tracks;
        for (const auto& [name, s] : summaries_) {
            keys += s.keys, kept += s.kept;
            tracks.push_back(json_object()
                                 .text("track", name)
                                 .count("keys", s.keys)
                                 .count("kept", s.kept)
                                 .number("largest_error", s.worst_deg)
                                 .number("largest_translation_error", s.worst_translation)
                                 .object());
        }
        return json_object()
                   .text("file", source_)
                   .number("tol", opts_.tol_deg)
                   .number("tol_translation", opts_.tol_translation)
                   .count("keys", keys)
                   .count("kept", kept)
                   .raw("tracks", fmt::format("[{}]", fmt::join(tracks, ", ")))
                   .object() +
               '\n';
    }

    reduce_options opts_;
    bool method_given_, report_json_;
    std::string source_;
    bool gltf_;
    reduction_observer* watch_;
    std::string name_;
    std::optional<track_reducer> reducer_;
    std::vector<std::pair<std::string, reduce_summary>> summaries_;
};

}  // namespace

std::unique_ptr<row_source> make_frame_rows(const resample_options& r, bool method_given, std::string source) {
    return std::make_unique<frame_rows>(r, method_given, std::move(source));
}

std::unique_ptr<row_source> make_key_rows() { return std::make_unique<key_rows>(); }

std::unique_ptr<row_source> make_reduced_rows(const reduce_options& r, bool method_given, bool report_json,
                                              std::string source, bool gltf, reduction_observer* watch) {
    return std::make_unique<reduced_rows>(r, method_given, report_json, std::move(source), gltf, watch);
}

}  // namespace keyrot::detail
