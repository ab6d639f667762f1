// SPDX-License-Identifier: MIT
#include "keyrot/describe.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "keyrot/convert.hpp"

namespace keyrot {
namespace {

/// Distance in radians of the sequence's middle angle from gimbal lock.
double gimbal_distance(quat q, const euler_seq& seq) {
    const double middle = to_euler(q, seq).angles[1];
    if (seq.axes[0] == seq.axes[2]) return std::fmin(middle, std::numbers::pi - middle);
    return std::numbers::pi / 2 - std::fabs(middle);
}

}  // namespace

track_describer::track_describer(std::string name, std::optional<euler_seq> euler, bool segments, method how,
                                 path way)
    : builder_(how, way, euler), steady_(how == method::slerp || how == method::step), way_(way),
      euler_(std::move(euler)), keep_segments_(segments) {
    info_.name = std::move(name);
    const peak none{-1, 0, 0, std::nullopt, std::nullopt};  // (below any speed)
    info_.speed = speed_info{how, none, none, 0, {}, 0};
}

void track_describer::measure(const segment& s) {
    speed_info& v = *info_.speed;
    const std::size_t from = segments_seen();
    const std::optional<double> frame = frames_[0], frame_to = frames_[1];
    frames_.pop_front();
    peak fastest{-1, 0, from, frame, frame_to};
    const double dt = s.t1 - s.t0;
    const segment_curve curve = s.curve();
    double sum = 0;  // Simpson's rule over the five points
    const double weights[] = {1, 4, 2, 4, 1};
    for (std::size_t j = 0; j < 5; ++j) {
        const double h = static_cast<double>(j) / 4, time = s.t0 + h * dt;
        const motion m = curve.rates(h);
        const double speed = from_radians(norm(m.velocity), angle_unit::degrees);
        const double acceleration = from_radians(norm(m.acceleration), angle_unit::degrees);
        if (speed > fastest.value) fastest.value = speed, fastest.time = time;
        if (acceleration > v.most_accelerated.value) v.most_accelerated = {acceleration, time, from, frame, frame_to};
        sum += weights[j] * speed;
    }
    settle(fastest, sum / 12 * dt);
}

void track_describer::settle(const peak& fastest, double angle) {
    speed_info& v = *info_.speed;
    speed_time_ += angle;
    if (fastest.value > v.fastest.value) v.fastest = fastest;
    window_.push_back(fastest);
    window_.back().angle_deg = angle;
    // A full window judges the segment in its middle (the first one, those before it too).
    if (window_.size() == spike_window) {
        judge_until(dropped_ + spike_window / 2 + 1, false);
        window_.pop_front();
        ++dropped_;
    }
}

void track_describer::judge_until(std::size_t end, bool last) {
    if (judged_ >= end) return;
    if (last || ++since_median_ >= spike_median_every) {
        std::array<double, spike_window> speeds{};
        for (std::size_t i = 0; i < window_.size(); ++i) speeds[i] = window_[i].value;
        const auto middle = speeds.begin() + static_cast<std::ptrdiff_t>(window_.size() / 2);
        std::nth_element(speeds.begin(), middle, speeds.begin() + static_cast<std::ptrdiff_t>(window_.size()));
        median_ = *middle, since_median_ = 0;
    }
    speed_info& v = *info_.speed;
    for (; judged_ < end; ++judged_) {
        const peak& p = window_[judged_ - dropped_];
        if (p.value > spike_times_median * median_ && p.angle_deg > spike_least_deg && v.spike_count++ < key_list::listed)
            v.spikes.push_back(p);
    }
}

void track_describer::finish() {
    segment s;
    while (builder_.pop(s, true)) measure(s);
    if (info_.keys < 2) {
        info_.speed.reset();
        return;
    }
    // The segments after the last window's middle (a short track's all) against it.
    judge_until(segments_seen(), true);
    info_.speed->mean = speed_time_ / (info_.end - info_.start);
}

void track_describer::add(const key& k) {
    track_info& info = info_;
    const std::size_t i = info.keys++;
    if (i == 0) info.start = k.time;
    info.end = k.time;
    if (std::find(info.given_as.begin(), info.given_as.end(), k.given_as) == info.given_as.end())
        info.given_as.push_back(k.given_as);
    if (k.renormalised) info.renormalised.add(i);
    info.signed_keys = info.signed_keys || (k.given_as != rep::matrix && k.given_as != rep::matrix4);
    info.quaternion_keys = info.quaternion_keys || k.given_as == rep::quat;
    if (k.given_as == rep::euler && euler_ && gimbal_distance(k.rotation, *euler_) <= to_radians(near_gimbal_deg, angle_unit::degrees))
        info.near_gimbal.add(i);
    if (i > 0) {
        const double gap = k.time - previous_time_;
        segment_info s;
        s.angle_deg = from_radians(geodesic_angle(previous_, k.rotation), angle_unit::degrees);
        s.speed_deg_s = s.angle_deg / gap;
        s.direct_long_way = dot(previous_, k.rotation) < 0;
        if (!info.largest || s.angle_deg > info.largest->angle_deg) {
            info.largest = s;
            info.largest_from = i - 1;
            info.largest_start = previous_time_, info.largest_end = k.time;
        }
        info.shortest_gap = std::min(info.shortest_gap, gap);
        info.longest_gap = std::max(info.longest_gap, gap);
        if (keep_segments_) info.segments.push_back(s);
        last_segment_ = s;
        if (k.given_as == rep::quat && previous_given_as_ == rep::quat && dot(previous_, k.rotation) < 0)
            info.flipped.add(i);
    }
    previous_given_as_ = k.given_as;
    if (steady_) {
        // One rate through each segment, slerp's its angle (the long way
        // where --path direct takes it) over its time: no curve needed, as
        // a track of dense keys has thousands of segments.
        if (i > 0) {
            const segment_info& s = keep_segments_ ? info.segments.back() : last_segment_;
            const double angle = info_.speed->how == method::step ? 0
                                 : way_ == path::direct && s.direct_long_way ? 360 - s.angle_deg
                                                                            : s.angle_deg;
            const double speed = angle / (k.time - previous_time_);
            const std::size_t from = segments_seen();
            if (from == 0) info_.speed->most_accelerated = {0, previous_time_, 0, previous_frame_, k.frame};
            settle({speed, previous_time_, from, previous_frame_, k.frame}, angle);
        }
    } else {
        builder_.add(k);
        frames_.push_back(k.frame);
        segment s;
        while (builder_.pop(s, false)) measure(s);
    }
    previous_ = k.rotation;
    previous_time_ = k.time;
    previous_frame_ = k.frame;
}

track_info describe(const track& t) {
    track_describer d(t.name, t.euler, true);
    for (const key& k : t.keys) d.add(k);
    d.finish();
    return d.info();
}

}  // namespace keyrot
