// SPDX-License-Identifier: MIT
#include "keyrot/compare.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "keyrot/convert.hpp"
#include "keyrot/tolerances.hpp"

namespace keyrot {
namespace {

constexpr int key_side = 0, answer_side = 1;

/// Whether frame numbers name the same moments in both tracks: stated (or
/// assumed) rates are equal; where a rate is implied by frames that carry
/// their times (rounded as they were written, say to 0.0417), the two
/// grids stay within half a frame of each other up to the last frame.
bool same_frames(const track_survey& e, const track_survey& a) {
    const double re = e.counted_rate(), ra = a.counted_rate();
    if (!e.rate_implied() && !a.rate_implied()) return re == ra;
    const double last = std::max(e.last_frame(), a.last_frame());
    return std::fabs(last / re - last / ra) <= 0.5 / std::max(re, ra);
}

}  // namespace

track_survey::track_survey(std::string name, std::optional<double> key_fps, double time_rounding)
    : name_(std::move(name)), key_fps_(key_fps), stored_rounding_(time_rounding) {}

track_survey::track_survey(const track& t)
    : track_survey(t.name, t.key_fps, t.interpolation ? t.interpolation->time_rounding : 0) {
    for (const key& k : t.keys) add(k);
}

void track_survey::add(const key& k) {
    ++keys_;
    any_weights_ = any_weights_ || !k.weights.empty();
    float32_ = float32_ && static_cast<double>(static_cast<float>(k.time)) == k.time;
    if (!k.frame) return;
    any_frame_ = true;
    last_frame_ = std::max(last_frame_, std::fabs(*k.frame));
    if (!k.has_time) frame_without_time_ = true;
    else if (k.time != 0 && *k.frame != 0) timed_ = std::pair(*k.frame, k.time);
}

bool track_survey::rate_implied() const { return !frame_without_time_ && timed_; }

double track_survey::counted_rate() const {
    return rate_implied() ? timed_->first / timed_->second : key_fps_.value_or(default_key_fps);
}

double track_survey::rounding() const { return std::max(stored_rounding_, float32_ ? 0x1p-24 : 0.0); }

double counted_rate(const track& t) { return track_survey(t).counted_rate(); }

comparer::comparer(const std::vector<track_survey>& key_tracks, const std::vector<track_survey>& answer_tracks,
                   const tolerances& tol, extra_rows extra, row_sink row)
    : tol_(tol), extra_(extra), row_(std::move(row)) {
    std::unordered_map<std::string_view, const track_survey*> in_answer;  // (names are unique within a file)
    for (const track_survey& a : answer_tracks) in_answer.emplace(a.name(), &a);
    // One track against one, either unnamed: the same track (a glTF file
    // names the node of an unnamed track).
    if (key_tracks.size() == 1 && answer_tracks.size() == 1 && key_tracks[0].name() != answer_tracks[0].name() &&
        (key_tracks[0].name().empty() || answer_tracks[0].name().empty())) {
        renamed_ = std::pair(answer_tracks[0].name(), key_tracks[0].name());
        in_answer = {{key_tracks[0].name(), &answer_tracks[0]}};
    }
    for (const track_survey& e : key_tracks) {
        pairing& p = pairs_[e.name()];
        p.in_key = true;
        summary_.weights = summary_.weights || e.any_weights();
        order_.push_back(e.name());
        const auto named = in_answer.find(e.name());
        if (named == in_answer.end()) {
            summary_.missing_tracks.push_back(e.name());
            continue;
        }
        const track_survey& a = *named->second;
        p.in_answer = true;
        // Frame numbers at different rates are different times: matched by time.
        p.by_frame = same_frames(e, a);
        p.rounding = std::max(e.rounding(), a.rounding());
        if (!p.by_frame && !summary_.frame_rates && e.any_frame() && a.any_frame())
            summary_.frame_rates = std::pair(e.counted_rate(), a.counted_rate());
    }
    for (const track_survey& a : answer_tracks) {
        if (renamed_) break;
        pairing& p = pairs_[a.name()];
        if (p.in_key) continue;
        p.in_answer = true;
        order_.push_back(a.name());
        summary_.extra_tracks.push_back(a.name());
    }
}

void comparer::from_key(const std::string& track, key k) { add(key_side, track, std::move(k)); }
void comparer::from_answer(const std::string& track, key k) { add(answer_side, track, std::move(k)); }

void comparer::add(int side, const std::string& track, key&& k) {
    const auto it = pairs_.find(side == answer_side && renamed_ && track == renamed_->first ? renamed_->second : track);
    if (it == pairs_.end() || !it->second.in_key || !it->second.in_answer) return put(unmatched(track, k, side));
    it->second.waiting[side].push_back(std::move(k));
    ++waiting_[side];
    settle(it->first, it->second);
}

/// Pairs the first keys waiting on both sides while it can: either they
/// match, or the earlier of them can match no key still to come (times
/// increase within a track), and is settled as unmatched.
void comparer::settle(const std::string& name, pairing& p) {
    auto& [e_keys, a_keys] = p.waiting;
    while (!e_keys.empty() && !a_keys.empty()) {
        const key& e = e_keys.front();
        const key& a = a_keys.front();
        const bool by_frame = p.by_frame && e.frame && a.frame;
        const double near = std::max(tol::match_time, std::fabs(e.time) * p.rounding);
        int settled = key_side;  // or answer_side, or both (-1)
        if (by_frame ? *e.frame == *a.frame : std::fabs(e.time - a.time) <= near) {
            put(matched(name, e, a));
            settled = -1;
        } else if (by_frame ? *e.frame < *a.frame : e.time < a.time) {
            put(unmatched(name, e, key_side));
        } else {
            put(unmatched(name, a, answer_side));
            settled = answer_side;
        }
        for (const int side : {key_side, answer_side})
            if (settled == -1 || settled == side) p.waiting[side].pop_front(), --waiting_[side];
    }
}

const comparison_summary& comparer::finish() {
    for (const std::string& name : order_) {
        pairing& p = pairs_.at(name);
        for (const int side : {key_side, answer_side}) {
            for (const key& k : p.waiting[side]) put(unmatched(name, k, side));
            waiting_[side] -= p.waiting[side].size();
            p.waiting[side].clear();
        }
    }
    return summary_;
}

void comparer::put(row_difference r) {
    comparison_summary& s = summary_;
    ++s.compared;
    if (r.angle_deg) {
        ++s.matched;
        if (!s.worst || *r.angle_deg > *s.worst->angle_deg) s.worst = r;
    } else {
        ++(r.extra ? s.extra : s.missing);
    }
    if (!r.pass()) {
        ++s.failed;
        if (!s.first_failure) s.first_failure = r;
    }
    if (row_) row_(r);
}

row_difference comparer::matched(const std::string& name, const key& e, const key& a) const {
    row_difference r{name,         e.frame,      e.time,
                     from_radians(geodesic_angle(e.rotation, a.rotation), angle_unit::degrees),
                     std::nullopt, std::nullopt, std::nullopt,
                     "",           false};
    if (*r.angle_deg > tol_.rotation_deg)
        r.problem = fmt::format("rotation differs by {:.6g} deg (tolerance {:g})", *r.angle_deg, tol_.rotation_deg);
    const auto vector = [&](const std::optional<vec3>& e_value, const std::optional<vec3>& a_value,
                            std::optional<double>& difference, std::string_view what) {
        if (!e_value) return;
        if (!a_value) {
            if (r.problem.empty()) r.problem = fmt::format("{} missing from the answer", what);
            return;
        }
        difference = norm(*e_value - *a_value);
        if (*difference > tol_.translation && r.problem.empty())
            r.problem = fmt::format("{} differs by {:.6g} (tolerance {:g})", what, *difference, tol_.translation);
    };
    vector(e.translation, a.translation, r.translation, "translation");
    vector(e.scale, a.scale, r.scale, "scale");
    const auto rate = [&](const std::optional<double>& tol, const std::optional<vec3>& e_value,
                          const std::optional<vec3>& a_value, std::optional<double>& difference, std::string_view what,
                          std::string_view unit) {
        if (!tol || !e_value) return;
        if (!a_value) {
            if (r.problem.empty()) r.problem = fmt::format("{} missing from the answer", what);
            return;
        }
        difference = from_radians(norm(*e_value - *a_value), angle_unit::degrees);
        if (*difference > *tol && r.problem.empty())
            r.problem = fmt::format("{} differs by {:.6g} {} (tolerance {:g})", what, *difference, unit, *tol);
    };
    static const frame_rates none;
    const frame_rates &er = e.rates ? *e.rates : none, &ar = a.rates ? *a.rates : none;
    rate(tol_.velocity, er.velocity, ar.velocity, r.velocity, "angular velocity", "deg/s");
    rate(tol_.acceleration, er.acceleration, ar.acceleration, r.acceleration, "angular acceleration", "deg/s^2");
    if (!e.weights.empty() && r.problem.empty()) {
        if (a.weights.size() != e.weights.size())
            r.problem = fmt::format("{} morph weights in the answer: expected {}", a.weights.size(), e.weights.size());
        else {
            double worst = 0;
            for (std::size_t j = 0; j < e.weights.size(); ++j) worst = std::max(worst, std::fabs(e.weights[j] - a.weights[j]));
            r.weights = worst;
            if (worst > tol_.translation)
                r.problem = fmt::format("weights differ by {:.6g} (tolerance {:g})", worst, tol_.translation);
        }
    }
    return r;
}

row_difference comparer::unmatched(const std::string& name, const key& k, int side) const {
    if (side == key_side)
        return {name, k.frame, k.time, std::nullopt, std::nullopt, std::nullopt, std::nullopt, "missing from the answer", false};
    return {name, k.frame, k.time, std::nullopt, std::nullopt, std::nullopt, std::nullopt,
            extra_ == extra_rows::fail ? "only in the answer" : "", true};
}

comparison compare_tracks(const std::vector<track>& key_tracks, const std::vector<track>& answer_tracks, const tolerances& tol,
                          extra_rows extra) {
    comparison out;
    std::vector<track_survey> e_surveys, a_surveys;
    std::unordered_map<std::string_view, const track*> by_name;
    for (const track& t : key_tracks) e_surveys.emplace_back(t);
    for (const track& t : answer_tracks) a_surveys.emplace_back(t), by_name.emplace(t.name, &t);
    comparer c(e_surveys, a_surveys, tol, extra, [&](const row_difference& r) { out.rows.push_back(r); });
    std::unordered_set<std::string_view> fed;
    const auto feed = [&](const track& t, bool is_key) {
        for (const key& k : t.keys) is_key ? c.from_key(t.name, k) : c.from_answer(t.name, k);
    };
    for (const track& e : key_tracks) {
        feed(e, true);
        if (const auto a = by_name.find(e.name); a != by_name.end()) feed(*a->second, false), fed.insert(e.name);
    }
    for (const track& a : answer_tracks)
        if (!fed.contains(a.name)) feed(a, false);
    static_cast<comparison_summary&>(out) = c.finish();
    return out;
}

}  // namespace keyrot
