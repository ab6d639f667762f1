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

track_info describe(const track& t) {
    track_info info;
    info.name = t.name;
    info.keys = t.keys.size();
    info.start = t.keys.front().time;
    info.end = t.keys.back().time;
    quat previous{};
    for (std::size_t i = 0; i < t.keys.size(); ++i) {
        const key& k = t.keys[i];
        if (std::find(info.given_as.begin(), info.given_as.end(), k.given_as) == info.given_as.end())
            info.given_as.push_back(k.given_as);
        if (k.renormalised) info.renormalised.push_back(i);
        info.signed_keys = info.signed_keys || (k.given_as != rep::matrix && k.given_as != rep::matrix4);
        if (k.euler && t.euler && gimbal_distance(k.rotation, *t.euler) <= to_radians(near_gimbal_deg, angle_unit::degrees))
            info.near_gimbal.push_back(i);
        quat aligned = k.rotation;
        if (i > 0) {
            const key& prev = t.keys[i - 1];
            segment_info s;
            s.angle_deg = from_radians(geodesic_angle(prev.rotation, k.rotation), angle_unit::degrees);
            s.speed_deg_s = s.angle_deg / (k.time - prev.time);
            s.direct_long_way = dot(prev.rotation, k.rotation) < 0;
            info.segments.push_back(s);
            if (dot(previous, aligned) < 0) {
                aligned = -aligned;
                info.flipped.push_back(i);
            }
        }
        previous = aligned;
    }
    return info;
}

}  // namespace keyrot
