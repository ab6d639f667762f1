#include "keyrot/compare.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "keyrot/convert.hpp"
#include "keyrot/tolerances.hpp"

namespace keyrot {
namespace {

/// Finds the key of a track that matches another key: the first by frame if
/// both have one, else by time (|dt| <= tol::match_time, or the times'
/// rounding as stored where that is more: 2^-24 of them in a glTF file). Binary searches of
/// the frames (sorted, ties by position) and of the times (which increase
/// strictly within a track) make that O(log n) rather than a scan, so that
/// long tracks compare in n log n.
class key_finder {
public:
    /// `by_frame`: frame numbers count at the same rate in both tracks;
    /// `rounding`: the relative rounding of either track's times as stored.
    key_finder(const track& t, bool by_frame, double rounding) : keys_(t.keys), by_frame_(by_frame), rounding_(rounding) {
        for (std::size_t i = 0; i < keys_.size(); ++i) {
            if (keys_[i].frame && by_frame) frames_.emplace_back(*keys_[i].frame, i);
            else without_frame_.push_back(i);
        }
        std::sort(frames_.begin(), frames_.end());
    }

    std::optional<std::size_t> find(const key& k) const {
        if (!by_frame_) return find_by_time(k);
        if (!k.frame) return find_by_time(k);
        const auto unframed = std::partition_point(without_frame_.begin(), without_frame_.end(),
                                                   [&](std::size_t i) { return too_early(keys_[i], k); });
        std::optional<std::size_t> found;
        if (unframed != without_frame_.end() && near(keys_[*unframed], k)) found = *unframed;
        const auto framed = std::lower_bound(frames_.begin(), frames_.end(), std::pair(*k.frame, std::size_t{0}));
        if (framed != frames_.end() && framed->first == *k.frame)
            found = std::min(found.value_or(framed->second), framed->second);
        return found;
    }

private:
    // Among keys in increasing time, those too early form a prefix, as
    // k.time - other.time only falls as other.time grows: the first key
    // after it is the one candidate.
    double tolerance(const key& k) const { return std::max(tol::match_time, std::fabs(k.time) * rounding_); }
    bool too_early(const key& other, const key& k) const {
        return other.time < k.time && k.time - other.time > tolerance(k);
    }
    bool near(const key& other, const key& k) const { return std::fabs(k.time - other.time) <= tolerance(k); }

    std::optional<std::size_t> find_by_time(const key& k) const {
        const auto it = std::partition_point(keys_.begin(), keys_.end(), [&](const key& other) { return too_early(other, k); });
        if (it == keys_.end() || !near(*it, k)) return std::nullopt;
        return static_cast<std::size_t>(it - keys_.begin());
    }

    const std::vector<key>& keys_;
    bool by_frame_;
    double rounding_;
    std::vector<std::pair<double, std::size_t>> frames_;  ///< (frame, index) of the keys that have one
    std::vector<std::size_t> without_frame_;
};

/// The relative rounding of a track's times as stored: a glTF file's own,
/// or that of 32-bit floats where every time is one (a glTF file's times
/// written out as decimals, 32.06666564941406 for 32.0666...).
double rounding_of(const track& t) {
    const double stored = t.interpolation ? t.interpolation->time_rounding : 0;
    const bool float32 = std::all_of(t.keys.begin(), t.keys.end(), [](const key& k) {
        return static_cast<double>(static_cast<float>(k.time)) == k.time;
    });
    return std::max(stored, float32 ? 0x1p-24 : 0.0);
}

/// The rate a track's frame numbers count at, and whether the frames'
/// own times imply it (then as precisely as those times were written).
struct frame_rate_of {
    double rate;
    bool implied;
};

frame_rate_of rate_of(const track& t) {
    const key* timed = nullptr;  // the last key whose frame and time give the rate
    for (const key& k : t.keys) {
        if (!k.frame) continue;
        if (!k.has_time) return {t.frame_rate(), false};
        if (k.time != 0 && *k.frame != 0) timed = &k;
    }
    if (!timed) return {t.frame_rate(), false};
    return {*timed->frame / timed->time, true};
}

/// Whether frame numbers name the same moments in both tracks: stated (or
/// assumed) rates are equal; where a rate is implied by frames that carry
/// their times (rounded as they were written, say to 0.0417), the two
/// grids stay within half a frame of each other up to the last frame.
bool same_frames(const track& e, const track& a) {
    const frame_rate_of re = rate_of(e), ra = rate_of(a);
    if (!re.implied && !ra.implied) return re.rate == ra.rate;
    double last = 0;
    for (const track* t : {&e, &a})
        for (const key& k : t->keys)
            if (k.frame) last = std::max(last, std::fabs(*k.frame));
    return std::fabs(last / re.rate - last / ra.rate) <= 0.5 / std::max(re.rate, ra.rate);
}

row_difference unmatched(const track& t, const key& k, const char* problem) {
    return {t.name, k.frame, k.time, std::nullopt, std::nullopt, std::nullopt, problem, false};
}

}  // namespace

double counted_rate(const track& t) { return rate_of(t).rate; }

comparison compare_tracks(const std::vector<track>& expected, const std::vector<track>& actual, const tolerances& tol,
                          extra_rows extra) {
    comparison out;
    std::vector<std::vector<bool>> used(actual.size());
    std::unordered_map<std::string_view, const track*> by_name;  // (names are unique within a file)
    for (std::size_t i = 0; i < actual.size(); ++i) {
        used[i].assign(actual[i].keys.size(), false);
        by_name.emplace(actual[i].name, &actual[i]);
    }

    for (const track& e : expected) {
        const auto named = by_name.find(e.name);
        const track* a = named == by_name.end() ? nullptr : named->second;
        if (!a) out.missing_tracks.push_back(e.name);
        // Frame numbers at different rates are different times: matched by time.
        const auto has_frames = [](const track& t) {
            return std::any_of(t.keys.begin(), t.keys.end(), [](const key& k) { return k.frame.has_value(); });
        };
        const bool same_rates = !a || same_frames(e, *a);
        if (!same_rates && !out.frame_rates && has_frames(e) && has_frames(*a))
            out.frame_rates = std::pair(counted_rate(e), counted_rate(*a));
        const std::optional<key_finder> finder =
            a ? std::optional<key_finder>(std::in_place, *a, same_rates,
                                          std::max(rounding_of(e), rounding_of(*a)))
              : std::nullopt;
        for (const key& k : e.keys) {
            const auto j = finder ? finder->find(k) : std::nullopt;
            if (!j) {
                out.rows.push_back(unmatched(e, k, "missing from ACTUAL"));
                ++out.missing;
                continue;
            }
            ++out.matched;
            used[static_cast<std::size_t>(a - actual.data())][*j] = true;
            const key& other = a->keys[*j];
            row_difference r{e.name, k.frame, k.time, from_radians(geodesic_angle(k.rotation, other.rotation),
                                                                   angle_unit::degrees),
                             std::nullopt, std::nullopt, "", false};
            if (*r.angle_deg > tol.rotation_deg)
                r.problem = fmt::format("rotation differs by {:.6g} deg (tolerance {:g})", *r.angle_deg, tol.rotation_deg);
            const auto vector = [&](const std::optional<vec3>& e_value, const std::optional<vec3>& a_value,
                                    std::optional<double>& difference, std::string_view what) {
                if (!e_value) return;
                if (!a_value) {
                    if (r.problem.empty()) r.problem = fmt::format("{} missing from ACTUAL", what);
                    return;
                }
                difference = norm(*e_value - *a_value);
                if (*difference > tol.translation && r.problem.empty())
                    r.problem = fmt::format("{} differs by {:.6g} (tolerance {:g})", what, *difference, tol.translation);
            };
            vector(k.translation, other.translation, r.translation, "translation");
            vector(k.scale, other.scale, r.scale, "scale");
            if (!out.worst || *r.angle_deg > *out.rows[*out.worst].angle_deg) out.worst = out.rows.size();
            out.rows.push_back(r);
        }
    }
    std::unordered_set<std::string_view> in_expected;
    for (const track& e : expected) in_expected.insert(e.name);
    for (const track& a : actual)
        if (!in_expected.contains(a.name)) out.extra_tracks.push_back(a.name);
    for (std::size_t i = 0; i < actual.size(); ++i)
        for (std::size_t j = 0; j < actual[i].keys.size(); ++j)
            if (!used[i][j]) {
                row_difference r = unmatched(actual[i], actual[i].keys[j], extra == extra_rows::fail ? "only in ACTUAL" : "");
                r.extra = true;
                out.rows.push_back(std::move(r));
                ++out.extra;
            }
    out.failed = static_cast<std::size_t>(std::count_if(out.rows.begin(), out.rows.end(), [](const auto& r) { return !r.pass(); }));
    return out;
}

}  // namespace keyrot
