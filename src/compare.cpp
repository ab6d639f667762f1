#include "keyrot/compare.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "keyrot/convert.hpp"
#include "keyrot/tolerances.hpp"

namespace keyrot {
namespace {

const track* find_track(const std::vector<track>& tracks, const std::string& name) {
    for (const track& t : tracks)
        if (t.name == name) return &t;
    return nullptr;
}

/// The key of `t` that matches `k`, by frame if both have one, else by time.
std::optional<std::size_t> match(const track& t, const key& k) {
    for (std::size_t i = 0; i < t.keys.size(); ++i) {
        const key& other = t.keys[i];
        if (k.frame && other.frame ? *k.frame == *other.frame : std::fabs(k.time - other.time) <= tol::match_time)
            return i;
    }
    return std::nullopt;
}

row_difference unmatched(const track& t, const key& k, const char* problem) {
    return {t.name, k.frame, k.time, std::nullopt, std::nullopt, problem};
}

}  // namespace

comparison compare_tracks(const std::vector<track>& expected, const std::vector<track>& actual, const tolerances& tol) {
    comparison out;
    std::vector<std::vector<bool>> used(actual.size());
    for (std::size_t i = 0; i < actual.size(); ++i) used[i].assign(actual[i].keys.size(), false);

    for (const track& e : expected) {
        const track* a = find_track(actual, e.name);
        for (const key& k : e.keys) {
            const auto j = a ? match(*a, k) : std::nullopt;
            if (!j) {
                out.rows.push_back(unmatched(e, k, "missing from ACTUAL"));
                continue;
            }
            used[static_cast<std::size_t>(a - actual.data())][*j] = true;
            const key& other = a->keys[*j];
            row_difference r{e.name, k.frame, k.time, from_radians(geodesic_angle(k.rotation, other.rotation),
                                                                   angle_unit::degrees),
                             std::nullopt, ""};
            if (*r.angle_deg > tol.rotation_deg)
                r.problem = fmt::format("rotation differs by {:.6g} deg (tolerance {:g})", *r.angle_deg, tol.rotation_deg);
            if (k.translation) {
                if (!other.translation) {
                    if (r.problem.empty()) r.problem = "translation missing from ACTUAL";
                } else {
                    r.translation = norm(*k.translation - *other.translation);
                    if (*r.translation > tol.translation && r.problem.empty())
                        r.problem = fmt::format("translation differs by {:.6g} (tolerance {:g})", *r.translation,
                                                tol.translation);
                }
            }
            if (!out.worst || *r.angle_deg > *out.rows[*out.worst].angle_deg) out.worst = out.rows.size();
            out.rows.push_back(r);
        }
    }
    for (std::size_t i = 0; i < actual.size(); ++i)
        for (std::size_t j = 0; j < actual[i].keys.size(); ++j)
            if (!used[i][j]) out.rows.push_back(unmatched(actual[i], actual[i].keys[j], "only in ACTUAL"));
    out.failed = static_cast<std::size_t>(std::count_if(out.rows.begin(), out.rows.end(), [](const auto& r) { return !r.pass(); }));
    return out;
}

}  // namespace keyrot
