// SPDX-License-Identifier: MIT
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

/// The same in seconds.
double tolerance(double time, const resample_options& opts) { return tolerance_frames(time, opts) / opts.fps; }

}  // namespace

std::pair<double, double> frame_span(double first, double last, const resample_options& opts) {
    // (+ 0: the ceiling of a time just below 0 is -0, which a glTF file would keep)
    return {std::ceil(first * opts.fps - tolerance_frames(first, opts)) + 0.0,
            std::floor(last * opts.fps + tolerance_frames(last, opts))};
}

void check_frame_range(const key& first, const key& last, const std::string& track_name, const resample_options& opts,
                       const std::string& source) {
    const double fps = opts.fps;
    const auto [first_frame, last_frame] = frame_span(first.time, last.time, opts);
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
        throw frame_limit_error(where(source, last.at),
                                fmt::format("{}keys from {} s to {} s make {:g} frames at {} fps: expected at most {:g}",
                                            track_name.empty() ? "" : fmt::format("track '{}': ", track_name),
                                            first.time, last.time, last_frame - first_frame + 1, fps, opts.max_frames));
}

vec3 channel_between(method how, double ta, const vec3& a, const vec3& out_a, double tb, const vec3& b, const vec3& in_b,
                     double time) {
    const double h = segment_fraction(ta, tb, time);
    switch (how) {
        case method::step: return a;
        case method::cubicspline: {
            const auto c = [](vec3 v) { return std::array<double, 4>{v.x, v.y, v.z, 0}; };
            const auto p = hermite(c(a), c(out_a), c(b), c(in_b), tb - ta, h);
            return {p[0], p[1], p[2]};
        }
        default: return (1 - h) * a + h * b;
    }
}

morph_weights channel_between(method how, double ta, const morph_weights& a, const morph_weights& out_a, double tb,
                              const morph_weights& b, const morph_weights& in_b, double time) {
    const double h = segment_fraction(ta, tb, time);
    morph_weights w(a.size());
    switch (how) {
        case method::step: return a;
        case method::cubicspline: hermite(a, out_a, b, in_b, tb - ta, h, w); return w;
        default:
            for (std::size_t j = 0; j < w.size(); ++j) w[j] = (1 - h) * a[j] + h * b[j];
            return w;
    }
}

template <class V>
value_channel<V>::value_channel(const resample_options& opts, method how, bool expected)
    : opts_(opts), how_(how), expected_(expected) {}

template <class V>
void value_channel<V>::add(double time, V value, V in, V out) {
    keys_.push_back({time, std::move(value), std::move(in), std::move(out)});
}

template <class V>
bool value_channel<V>::at(double time, bool end, std::optional<V>& value) {
    if (!expected_) return true;
    auto& keys = keys_;
    const auto tol = [this](double key_time) { return tolerance(key_time, opts_); };
    std::size_t j = 0;  // the first key at or after the frame
    while (j < keys.size() && keys[j].time < time - tol(keys[j].time)) ++j;
    if (j == keys.size()) {
        if (!end) return false;
        if (!keys.empty()) value = keys.back().value;
    } else if (keys[j].time - time <= tol(keys[j].time) || j == 0) {
        // Of keys within tolerance, the nearer; one not yet here may be nearer still.
        while (j + 1 < keys.size() && std::fabs(keys[j + 1].time - time) < std::fabs(keys[j].time - time)) ++j;
        if (!end && j + 1 == keys.size() && keys[j].time != time && keys[j].time - time <= tol(keys[j].time))
            return false;
        value = keys[j].value;
    } else {
        const channel_key &a = keys[j - 1], &b = keys[j];
        value = channel_between(how_, a.time, a.value, a.out, b.time, b.value, b.in, time);
    }
    // keep the key before the next frame's segment
    if (j > 1) keys.erase(keys.begin(), keys.begin() + static_cast<std::ptrdiff_t>(j - 1));
    return true;
}

template class value_channel<vec3>;
template class value_channel<morph_weights>;

track_resampler::track_resampler(const resample_options& opts, const std::optional<euler_seq>& seq, channels carried,
                                 frame_sink emit, arc_frame_sink* arc_frames)
    : opts_(opts),
      builder_(opts.how, opts.way, seq),
      emit_(std::move(emit)),
      vectors_(carried.any()),
      translation_(opts, opts.translation_how.value_or(opts.how), carried.translation),
      scale_(opts, opts.scale_how.value_or(opts.how), carried.scale),
      weights_(opts, opts.weights_how.value_or(opts.how), carried.weights > 0),
      rates_(opts.velocity || opts.acceleration) {
    // Only frames of a rotation alone go there: rates, translations, scales
    // and weights are worked out here, frame by frame.
    const bool arcs = opts.how == method::slerp || opts.how == method::squad;
    arc_frames_ = arcs && !vectors_ && !rates_ ? arc_frames : nullptr;
}

void track_resampler::add(const key& k) {
    if (!started_) {
        started_ = true;
        next_frame_ = frame_span(k.time, k.time, opts_).first;
    }
    if (k.translation || k.scale || !k.weights.empty()) {
        static const full_spline_key none;
        const full_spline_key& spline = k.spline ? *k.spline : none;
        if (k.translation) translation_.add(k.time, *k.translation, spline.translation_in, spline.translation_out);
        if (k.scale) scale_.add(k.time, *k.scale, spline.scale_in, spline.scale_out);
        if (!k.weights.empty()) {
            morph_weights in = spline.weights_in, out = spline.weights_out;  // (zero where none are given)
            in.resize(k.weights.size()), out.resize(k.weights.size());
            weights_.add(k.time, k.weights, std::move(in), std::move(out));
        }
        resolve_vectors(false);
    }
    last_key_ = builder_.add(k);
    last_time_ = k.time;
    while (builder_.pop(popped_, false)) frames_of(popped_);
}

void track_resampler::finish() {
    if (!started_) return;
    while (builder_.pop(popped_, true)) frames_of(popped_);
    frames_until(last_time_, last_key_);
    resolve_vectors(true);
}

void track_resampler::frames_of(const segment& s) {
    // frames in [t0, t1): at t0 the key itself, inside by the curve; a frame
    // within tolerance of t1 belongs to the next key. Within tolerance of
    // both (keys closer together than it), the nearer key's, so that at a
    // key's exact time the frame is that key.
    const auto time = [this] { return next_frame_ / opts_.fps; };
    const auto tolerance = [this](double key_time) { return keyrot::tolerance(key_time, opts_); };
    const auto in_segment = [&] { return time() <= s.t1 - tolerance(s.t1); };
    const double from_start = std::fabs(time() - s.t0);
    const bool at_start = from_start <= tolerance(s.t0) && from_start <= std::fabs(time() - s.t1);
    if (rates_) return rated_frames_of(s, at_start);
    if (at_start) out(next_frame_, s.q0), ++next_frame_;
    // Dense keys (motion capture at 120 Hz, say) leave most segments without
    // a frame inside: they never set up a curve.
    if (!in_segment()) return;
    if (arc_frames_) {
        arc_frames_->keys(s.keys_for_arcs());
        for (; in_segment(); ++next_frame_) arc_frames_->frame(next_frame_, time());
        return;
    }
    const segment_curve curve = s.curve();
    for (; in_segment(); ++next_frame_) out(next_frame_, curve.at(segment_fraction(s.t0, s.t1, time())));
}

void track_resampler::rated_frames_of(const segment& s, bool at_start) {
    // as frames_of, each frame's rates set before it goes out; every
    // segment's curve is set up, for its last rates at least
    const auto time = [this] { return next_frame_ / opts_.fps; };
    const double end = s.t1 - keyrot::tolerance(s.t1, opts_);
    const segment_curve curve = s.curve();
    if (at_start) rates_now_ = curve.rates(0), out(next_frame_, s.q0), ++next_frame_;
    for (; time() <= end; ++next_frame_) {
        const double h = segment_fraction(s.t0, s.t1, time());
        rates_now_ = curve.rates(h);
        out(next_frame_, curve.at(h));
    }
    rates_now_ = curve.rates(1);  // the last key's, should no segment follow
}

void track_resampler::frames_until(double time, quat q) {
    for (const double last = frame_span(time, time, opts_).second; next_frame_ <= last; ++next_frame_) out(next_frame_, q);
}

void track_resampler::out(double frame, quat q) {
    if (emitted_ && dot(previous_, q) < 0) q = -q;
    previous_ = q;
    emitted_ = true;
    sample s;
    s.frame = frame;
    s.time = frame / opts_.fps;
    s.rotation = q;
    if (rates_) return rated_out(s);
    // Nothing waiting, and the keys of its translation, scale and weights here: straight out.
    if (!vectors_ || (pending_.empty() && with_vectors(s, false))) return emit_(s);
    pending_.push_back({s, {}});
}

void track_resampler::rated_out(sample& s) {
    const motion m = opts_.rates_frame == motion_frame::fixed ? in_fixed_frame(s.rotation, rates_now_) : rates_now_;
    frame_rates rates;
    if (opts_.velocity) rates.velocity = m.velocity;
    if (opts_.acceleration) rates.acceleration = m.acceleration;
    if (!vectors_ || (pending_.empty() && with_vectors(s, false))) {
        rates_out_ = rates, s.rates = &rates_out_;
        return emit_(s);
    }
    pending_.push_back({s, rates});
}

bool track_resampler::with_vectors(sample& s, bool end) {
    std::optional<morph_weights> w;
    if (!translation_.at(s.time, end, s.translation) || !scale_.at(s.time, end, s.scale) ||
        !weights_.at(s.time, end, w))
        return false;
    if (w) s.weights = weights_now_ = std::move(*w);
    return true;
}

void track_resampler::resolve_vectors(bool end) {
    for (; !pending_.empty() && with_vectors(pending_.front().s, end); pending_.pop_front()) {
        sample& s = pending_.front().s;
        if (rates_) rates_out_ = pending_.front().rates, s.rates = &rates_out_;
        emit_(s);
    }
}

void resample(const track& t, const resample_options& opts, const std::string& source, const frame_sink& emit) {
    check_frame_range(t.keys.front(), t.keys.back(), t.name, opts, source);
    channels carried;
    for (const key& k : t.keys) carried |= channels_of(k);
    track_resampler r(opts, t.euler, carried, emit);
    for (const key& k : t.keys) r.add(k);
    r.finish();
}

}  // namespace keyrot
