// SPDX-License-Identifier: MIT
#include "keyrot/reduce.hpp"

#include <algorithm>
#include <cmath>

#include "core/arc_screen.hpp"
#include "keyrot/convert.hpp"
#include "keyrot/error.hpp"
#include "keyrot/resample.hpp"

namespace keyrot {
namespace {

double distance(const std::optional<vec3>& a, const std::optional<vec3>& b) { return a && b ? norm(*a - *b) : 0; }

/// Only keys of the same channels as both ends are played from keys `from`
/// and `to` (neighbours, with none between, always are).
bool played_between(const key& a, const key& b, std::size_t from, std::size_t to) {
    return channels_of(a) == channels_of(b) || to == from + 1;
}

/// How far, in degrees, key k's rotation is from q; or 0 where that is
/// plainly less than `floor` degrees (no atan2 then).
double rotation_error(quat q, const key& k, double floor = 0) {
    const half_angle half = geodesic_half_angle(q, k.rotation);
    // atan2(s, c) <= s / c for c > 0, which is the angle to a hair where it is small.
    if (half.cos > 0 && from_radians(2 * half.sin / half.cos, angle_unit::degrees) * (1 + 1e-12) < floor) return 0;
    return from_radians(geodesic_angle(half), angle_unit::degrees);
}

/// A vector channel between keys `a` and `b` at `h`, as resample plays it.
std::optional<vec3> vector_at(const std::optional<vec3>& a, const std::optional<vec3>& b, double h, method how) {
    if (!a || !b) return std::nullopt;
    return channel_between(how, 0, *a, {}, 1, *b, {}, h);
}

/// The largest difference of a weight of `k` from the weights between keys
/// `a` and `b` at `h`, as resample plays them, or from `a`'s with `b` = a.
double weights_distance(const morph_weights& a, const morph_weights& b, double h, method how, const morph_weights& k) {
    if (a.empty() || k.empty()) return 0;
    const morph_weights w = channel_between(how, 0, a, {}, 1, b, {}, h);
    double worst = 0;
    for (std::size_t j = 0; j < w.size(); ++j) worst = std::max(worst, std::fabs(w[j] - k[j]));
    return worst;
}

}  // namespace

track_reducer::track_reducer(const reduce_options& opts, const std::optional<euler_seq>& seq, std::string source,
                             std::function<void(const key&)> keep)
    : opts_(opts), seq_(seq), source_(std::move(source)), keep_(std::move(keep)), builder_(opts.how, opts.way, seq),
      sin_half_tol_(arc_screen::sin_half(opts.tol_deg)) {
    check_method(opts.how, seq);
    if (opts.how == method::cubicspline)
        throw option_error(option::method, "reduce plays keys as slerp, nlerp, squad, step or euler, not cubicspline "
                                           "(a CUBICSPLINE track's tangents belong to the keys it has)");
    if (opts.how == method::cubic)
        throw option_error(option::method, "reduce plays keys as slerp, nlerp, squad, step or euler, not cubic "
                                           "(each of its segments moves with every key, so no key can be dropped "
                                           "with a guarantee)");
}

segment track_reducer::segment_between(std::size_t from, std::size_t to, std::optional<std::size_t> before,
                                       std::optional<std::size_t> after) const {
    segment_builder& builder = builder_;
    builder.clear();
    if (before) builder.add(keys_[*before]);
    builder.add(keys_[from]);
    builder.add(keys_[to]);
    if (after) builder.add(keys_[*after]);
    segment s;
    do builder.pop(s, true);
    while (s.t0 != keys_[from].time);
    return s;
}

double track_reducer::translation_error(const key& a, const key& b, double h, const key& k) const {
    return std::max({distance(vector_at(a.translation, b.translation, h, opts_.translation_how.value_or(opts_.how)),
                              k.translation),
                     distance(vector_at(a.scale, b.scale, h, opts_.scale_how.value_or(opts_.how)), k.scale),
                     weights_distance(a.weights, b.weights, h, opts_.weights_how.value_or(opts_.how), k.weights)});
}

track_reducer::errors track_reducer::between(std::size_t from, std::size_t to, std::optional<std::size_t> before,
                                             std::optional<std::size_t> after, bool whole, double floor) const {
    floor = std::min(floor, opts_.tol_deg);  // a key out of tolerance is always worked out
    const key& a = keys_[from];
    const key& b = keys_[to];
    errors e;
    if (!played_between(a, b, from, to)) return {false, 0, 0, from + 1};
    const segment s = segment_between(from, to, before, after);
    const segment_curve curve = s.curve();
    double bad_deg = -1, bad_translation = -1;
    for (std::size_t i = from + 1; i < to && (e.ok || whole); ++i) {
        const key& k = keys_[i];
        if (channels_of(k) != channels_of(a)) return {false, e.deg, e.translation, i};
        const double h = (k.time - a.time) / (b.time - a.time);
        const double deg = rotation_error(curve.at(h), k, floor);
        const double translation = translation_error(a, b, h, k);
        e.deg = std::max(e.deg, deg), e.translation = std::max(e.translation, translation);
        if (deg <= opts_.tol_deg && translation <= opts_.tol_translation) continue;
        e.ok = false;
        // The worst key out: by its rotation, or by its translation where no rotation is out.
        const double rotation_out = deg > opts_.tol_deg ? deg : 0;
        if (rotation_out > bad_deg || (rotation_out == bad_deg && translation > bad_translation))
            e.bad = i, bad_deg = rotation_out, bad_translation = translation;
    }
    return e;
}

track_reducer::reach track_reducer::reaches(std::size_t to, bool last) const {
    const auto exactly = [&] {
        // (the errors below the largest so far are not worked out: they change nothing the summary says)
        const errors e = between(0, to, std::nullopt, std::nullopt, false, summary_.worst_deg);
        return reach{e.ok, e.deg, true, e.translation};
    };
    // The search's last probe is kept if it holds, and measured exactly
    // then while the largest error so far is below any bound the screen
    // gives (keys on the arcs but for rounding): checked exactly at once, it
    // needs no second pass.
    if (opts_.how != method::slerp || (last && summary_.worst_deg < arc_screen::most_deg(0))) return exactly();
    const key& a = keys_[0];
    const key& b = keys_[to];
    if (!played_between(a, b, 0, to)) return {};
    // The keys with the signs the path gives them, without a segment (it is made only if a key needs it).
    const quat qa = a.rotation, qb = builder_.signed_after(qa, b.rotation);
    arc_screen screen(qa, qb, sin_half_tol_);
    if (!screen.usable()) return exactly();
    std::optional<segment_curve> curve;  // set up for the first key the screen leaves unsure
    bool screened = false;                               // a key the screen found within
    double sin_off_sq = 0, exact_deg = 0, translation = 0;  // the largest
    for (std::size_t i = 1; i < to; ++i) {
        const key& k = keys_[i];
        if (channels_of(k) != channels_of(a)) return {};
        const double h = (k.time - a.time) / (b.time - a.time);
        const arc_screen::finding f = screen.at(h, k.rotation);
        switch (f.v) {
            case arc_screen::verdict::beyond: return {};
            case arc_screen::verdict::within: screened = true, sin_off_sq = std::max(sin_off_sq, f.sin_off_sq); break;
            case arc_screen::verdict::unsure: {
                if (!curve) curve = segment_between(0, to).curve();
                const double deg = rotation_error(curve->at(h), k);
                if (!(deg <= opts_.tol_deg)) return {};
                exact_deg = std::max(exact_deg, deg);
            }
        }
        const double moved = translation_error(a, b, h, k);
        if (!(moved <= opts_.tol_translation)) return {};
        translation = std::max(translation, moved);
    }
    if (!screened) return {true, exact_deg, true, translation};
    return {true, std::max(arc_screen::most_deg(sin_off_sq), exact_deg), false, translation};
}

track_reducer::errors track_reducer::kept_errors(const reach& r) const {
    // A bound below the largest error so far changes nothing the summary says.
    if (r.deg_exact || r.deg < summary_.worst_deg) return {true, r.deg_exact ? r.deg : 0, r.translation};
    return between(0, good_, std::nullopt, std::nullopt, false, summary_.worst_deg);
}

void track_reducer::add(const key& k) {
    if (k.spline)
        throw input_error(where(source_, k.at),
                          "a CUBICSPLINE key: expected LINEAR or STEP keys, whose values are the "
                          "curve (resample the track first)");
    keys_.push_back(k);
    if (summary_.keys++ == 0) {
        first_ = k;
        if (opts_.how != method::squad) emit(0, {});
        held_ = true;
    }
    if (held_) {  // (once the track has moved, how far from the first key is never asked again)
        from_first_deg_ = std::max(from_first_deg_, rotation_error(first_.rotation, k));
        from_first_translation_ = std::max(
            {from_first_translation_, distance(first_.translation, k.translation), distance(first_.scale, k.scale),
             weights_distance(first_.weights, first_.weights, 0, method::step, k.weights)});
        if (channels_of(k) != channels_of(first_)) from_first_translation_ = INFINITY;
        if (!(from_first_deg_ <= opts_.tol_deg && from_first_translation_ <= opts_.tol_translation)) {
            held_ = false;  // the track moves: the keys kept meanwhile go out
            for (const key& p : pending_) keep_(p);
            pending_.clear();
        }
    }
    if (opts_.how != method::squad) advance(false);
}

void track_reducer::advance(bool end) {
    while (keys_.size() > 1) {
        const std::size_t newest = keys_.size() - 1;
        if (good_ == 0) good_ = 1, good_reach_ = reach{.ok = true};  // neighbours: nothing between them
        const std::size_t limit = std::min(2 * good_, max_stretch);
        if (limit > newest && !end) return;  // the next key to try has not come
        const std::size_t probe = std::min(limit, newest);
        if (probe != good_) {
            // (a probe that holds at the longest stretch, or at the end, is kept)
            reach r = reaches(probe, probe == max_stretch || (end && probe == newest));
            if (r.ok) {
                good_ = probe, good_reach_ = r;
                continue;
            }
            for (std::size_t bad = probe; bad - good_ > 1;) {
                const std::size_t mid = good_ + (bad - good_) / 2;
                if ((r = reaches(mid, bad - good_ == 2)).ok)
                    good_ = mid, good_reach_ = r;
                else
                    bad = mid;
            }
        }
        // Nothing farther to try (the end, or the longest stretch): good_ is kept.
        emit(good_, kept_errors(good_reach_));
        keys_.erase(keys_.begin(), keys_.begin() + static_cast<std::ptrdiff_t>(good_));
        good_ = 0;
    }
}

void track_reducer::emit(std::size_t i, const errors& e) {
    summary_.worst_deg = std::max(summary_.worst_deg, e.deg);
    summary_.worst_translation = std::max(summary_.worst_translation, e.translation);
    ++summary_.kept;
    if (held_ && summary_.kept > 1)
        pending_.push_back(keys_[i]);
    else
        keep_(keys_[i]);
}

void track_reducer::finish() {
    if (summary_.keys == 0) return;
    // Within tolerance of the first key everywhere: that key, held (the
    // methods but squad gave it out at once).
    if (held_) {
        if (opts_.how == method::squad) keep_(first_);
        summary_ = {summary_.keys, 1, from_first_deg_, from_first_translation_};
        return;
    }
    if (opts_.how == method::squad) return reduce_squad();
    advance(true);
}

/// Squad's curve between two kept keys bends with the kept keys either
/// side, so the greedy pass guesses them (the key kept before, and the key
/// as far after as the stretch is long); then the track is played from the
/// kept keys, and where a key is out of tolerance it is kept too, until
/// none is.
void track_reducer::reduce_squad() {
    std::vector<std::size_t> kept{0};
    const std::size_t last = keys_.size() - 1;
    while (kept.back() != last) {
        const std::size_t from = kept.back();
        const auto before = kept.size() > 1 ? std::optional(kept[kept.size() - 2]) : std::nullopt;
        const auto check = [&](std::size_t to) {
            return between(from, to, before, to < last ? std::optional(std::min(last, 2 * to - from)) : std::nullopt)
                .ok;
        };
        std::size_t good = from + 1, bad = last + 1;
        while (good < last && bad == last + 1) {
            const std::size_t probe = std::min(2 * good - from, last);
            (check(probe) ? good : bad) = probe;
        }
        while (bad - good > 1) {
            const std::size_t mid = good + (bad - good) / 2;
            (check(mid) ? good : bad) = mid;
        }
        kept.push_back(good);
    }
    // A stretch's curve bends with the kept keys either side of it.
    const auto stretch = [&](std::size_t j) {
        return between(kept[j], kept[j + 1], j > 0 ? std::optional(kept[j - 1]) : std::nullopt,
                       j + 2 < kept.size() ? std::optional(kept[j + 2]) : std::nullopt, true);
    };
    for (std::size_t j = 0; j + 1 < kept.size();) {
        const errors e = stretch(j);
        if (e.ok) {
            ++j;
            continue;
        }
        // The key farthest out is kept too, which bends the stretches either side: back to the one before.
        kept.insert(kept.begin() + static_cast<std::ptrdiff_t>(j) + 1, e.bad);
        j = j > 0 ? j - 1 : 0;
    }
    for (std::size_t j = 0; j + 1 < kept.size(); ++j) {
        const errors e = stretch(j);
        summary_.worst_deg = std::max(summary_.worst_deg, e.deg);
        summary_.worst_translation = std::max(summary_.worst_translation, e.translation);
    }
    for (const std::size_t i : kept) keep_(keys_[i]);
    summary_.kept = kept.size();
}

}  // namespace keyrot
