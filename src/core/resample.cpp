#include "keyrot/resample.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "keyrot/tolerances.hpp"

namespace keyrot {

namespace {

/// How far, in frames, a frame may be from a key at `time` and count as at it.
double tolerance_frames(double time, const resample_options& opts) {
    return std::max(tol::grid_frames, std::fabs(time) * opts.fps * opts.time_rounding);
}

}  // namespace

void check_frame_range(const key& first, const key& last, const std::string& track_name, const resample_options& opts,
                       const std::string& source) {
    const double fps = opts.fps;
    const double first_frame = std::ceil(first.time * fps - tolerance_frames(first.time, opts));
    const double last_frame = std::floor(last.time * fps + tolerance_frames(last.time, opts));
    // Frame numbers must be exact integers in a double.
    constexpr double max_frame_number = 9007199254740992.0;  // 2^53
    for (const key* k : {&first, &last}) {
        const double frame = k == &first ? first_frame : last_frame;
        if (std::fabs(frame) >= max_frame_number)
            throw input_error(where(source, k->at), fmt::format("key time {} s is frame {:g} at {} fps: expected frames "
                                                               "within +-2^53",
                                                               k->time, frame, fps));
    }
    if (last_frame - first_frame + 1 > opts.max_frames)
        throw input_error(where(source, last.at),
                          fmt::format("{}keys from {} s to {} s make {:g} frames at {} fps: expected at most {:g} "
                                      "(--max-frames N raises the limit)",
                                      track_name.empty() ? "" : fmt::format("track '{}': ", track_name), first.time,
                                      last.time, last_frame - first_frame + 1, fps, opts.max_frames));
}

track_resampler::track_resampler(const resample_options& opts, const std::optional<euler_seq>& seq, bool translations,
                                 frame_sink emit)
    : opts_(opts),
      builder_(opts.how, opts.way, seq),
      emit_(std::move(emit)),
      translations_(translations),
      translation_how_(opts.translation_how.value_or(opts.how)) {}

void track_resampler::add(const key& k) {
    if (!started_) {
        started_ = true;
        // (+ 0: the ceiling of a time just below 0 is -0, which a glTF file would keep)
        next_frame_ = std::ceil(k.time * opts_.fps - tolerance_frames(k.time, opts_)) + 0.0;
    }
    if (k.translation) {
        const spline_key spline = k.spline.value_or(spline_key{});
        translation_keys_.push_back({k.time, *k.translation, spline.translation_in, spline.translation_out});
        resolve_translations(false);
    }
    last_key_ = builder_.add(k);
    last_time_ = k.time;
    segment s;
    while (builder_.pop(s, false)) frames_of(s);
}

void track_resampler::finish() {
    if (!started_) return;
    segment s;
    while (builder_.pop(s, true)) frames_of(s);
    frames_until(last_time_, last_key_);
    resolve_translations(true);
}

double track_resampler::tolerance(double key_time) const { return tolerance_frames(key_time, opts_) / opts_.fps; }

void track_resampler::frames_of(const segment& s) {
    // frames in [t0, t1): at t0 the key itself, inside by the curve; a frame
    // within tolerance of t1 belongs to the next key. Within tolerance of
    // both (keys closer together than it), the nearer key's, so that at a
    // key's exact time the frame is that key.
    const auto time = [this] { return next_frame_ / opts_.fps; };
    const auto in_segment = [&] { return time() <= s.t1 - tolerance(s.t1); };
    const double from_start = std::fabs(time() - s.t0);
    if (from_start <= tolerance(s.t0) && from_start <= std::fabs(time() - s.t1)) out(next_frame_, s.q0), ++next_frame_;
    // Dense keys (motion capture at 120 Hz, say) leave most segments without
    // a frame inside: they never set up a curve.
    if (!in_segment()) return;
    const segment_curve curve = s.curve();
    for (; in_segment(); ++next_frame_) out(next_frame_, curve.at((time() - s.t0) / (s.t1 - s.t0)));
}

void track_resampler::frames_until(double time, quat q) {
    for (; next_frame_ / opts_.fps <= time + tolerance(time); ++next_frame_) out(next_frame_, q);
}

void track_resampler::out(double frame, quat q) {
    if (emitted_ && dot(previous_, q) < 0) q = -q;
    previous_ = q;
    emitted_ = true;
    sample s;
    s.frame = frame;
    s.time = frame / opts_.fps;
    s.rotation = q;
    if (!translations_) {
        emit_(s);
        return;
    }
    pending_.push_back(s);
    resolve_translations(false);
}

vec3 track_resampler::translation_between(const translation_key& a, const translation_key& b, double time) const {
    const double h = (time - a.time) / (b.time - a.time);
    switch (translation_how_) {
        case method::step: return a.value;
        case method::cubicspline: {
            const auto c = [](vec3 v) { return std::array<double, 4>{v.x, v.y, v.z, 0}; };
            const auto p = hermite(c(a.value), c(a.out), c(b.value), c(b.in), b.time - a.time, h);
            return {p[0], p[1], p[2]};
        }
        default: return (1 - h) * a.value + h * b.value;
    }
}

void track_resampler::resolve_translations(bool end) {
    // The translation channel: linear between the keys that carry one (held
    // for step, Hermite for cubicspline), held before the first and after
    // the last of them. A frame waits until the first translation key at or
    // after it has arrived.
    auto& keys = translation_keys_;
    while (!pending_.empty()) {
        sample& s = pending_.front();
        std::size_t j = 0;  // the first translation key at or after the frame
        while (j < keys.size() && keys[j].time < s.time - tolerance(keys[j].time)) ++j;
        if (j == keys.size()) {
            if (!end) return;
            if (!keys.empty()) s.translation = keys.back().value;
        } else if (keys[j].time - s.time <= tolerance(keys[j].time) || j == 0) {
            // Of keys within tolerance, the nearer; one not yet here may be nearer still.
            while (j + 1 < keys.size() && std::fabs(keys[j + 1].time - s.time) < std::fabs(keys[j].time - s.time)) ++j;
            if (!end && j + 1 == keys.size() && keys[j].time != s.time && keys[j].time - s.time <= tolerance(keys[j].time))
                return;
            s.translation = keys[j].value;
        } else {
            s.translation = translation_between(keys[j - 1], keys[j], s.time);
        }
        emit_(s);
        pending_.pop_front();
        // keep the key before the next frame's segment
        while (keys.size() > 1 && j > 1) keys.pop_front(), --j;
    }
}

void resample(const track& t, const resample_options& opts, const std::string& source, const frame_sink& emit) {
    check_frame_range(t.keys.front(), t.keys.back(), t.name, opts, source);
    bool translations = false;
    for (const key& k : t.keys) translations = translations || k.translation.has_value();
    track_resampler r(opts, t.euler, translations, emit);
    for (const key& k : t.keys) r.add(k);
    r.finish();
}

}  // namespace keyrot
