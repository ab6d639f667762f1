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

track_describer::track_describer(std::string name, std::optional<euler_seq> euler, bool segments)
    : euler_(std::move(euler)), keep_segments_(segments) {
    info_.name = std::move(name);
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
    if (k.euler && euler_ && gimbal_distance(k.rotation, *euler_) <= to_radians(near_gimbal_deg, angle_unit::degrees))
        info.near_gimbal.add(i);
    quat aligned = k.rotation;
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
        if (dot(aligned_, aligned) < 0) {
            aligned = -aligned;
            info.flipped.add(i);
        }
    }
    aligned_ = aligned;
    previous_ = k.rotation;
    previous_time_ = k.time;
}

track_info describe(const track& t) {
    track_describer d(t.name, t.euler, true);
    for (const key& k : t.keys) d.add(k);
    return d.info();
}

}  // namespace keyrot
