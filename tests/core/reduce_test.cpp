// SPDX-License-Identifier: MIT
// track_reducer: which keys a few small tracks keep, worked out by hand.
#include <doctest/doctest.h>

#include <cmath>

#include "keyrot/reduce.hpp"

using namespace keyrot;

namespace {

/// The times of the keys reduce keeps of keys at times 0, 1, 2, ... with rotations `qs`.
std::vector<double> kept_times(const std::vector<quat>& qs, reduce_options opts = {},
                               const std::vector<std::optional<vec3>>& moves = {}) {
    std::vector<double> out;
    track_reducer r(opts, std::nullopt, "test", [&](const key& k) { out.push_back(k.time); });
    for (std::size_t i = 0; i < qs.size(); ++i) {
        key k;
        k.time = static_cast<double>(i);
        k.rotation = qs[i];
        if (i < moves.size()) k.translation = moves[i];
        r.add(k);
    }
    r.finish();
    CHECK(r.summary().keys == qs.size());
    CHECK(r.summary().kept == out.size());
    return out;
}

/// `deg` degrees about z.
quat about_z(double deg) {
    const double h = deg * M_PI / 360;
    return {std::cos(h), 0, 0, std::sin(h)};
}

}  // namespace

TEST_CASE("reduce: a turn at constant speed is its two ends, with slerp") {
    std::vector<quat> qs;
    for (int i = 0; i <= 10; ++i) qs.push_back(about_z(15.0 * i));  // 150 degrees
    CHECK(kept_times(qs) == std::vector<double>{0, 10});
    // 15 degrees a key to 300: slerp from 0 to 300 would take the short way round (-60).
    for (int i = 11; i <= 20; ++i) qs.push_back(about_z(15.0 * i));
    const auto kept = kept_times(qs);
    REQUIRE(kept.size() >= 3);
    for (std::size_t i = 1; i < kept.size(); ++i)
        CHECK(15 * (kept[i] - kept[i - 1]) <= 180);  // never more than half a turn
}

TEST_CASE("reduce: a key off the arc by more than the tolerance stays") {
    std::vector<quat> qs{about_z(0), about_z(10), about_z(20.02), about_z(30), about_z(40)};
    CHECK(kept_times(qs) == std::vector<double>{0, 2, 4});  // 0.02 deg off: out of 0.01
    reduce_options loose;
    loose.tol_deg = 0.05;
    CHECK(kept_times(qs, loose) == std::vector<double>{0, 4});
}

TEST_CASE("reduce: a constant track is its first key; equal runs keep their ends") {
    CHECK(kept_times(std::vector<quat>(7, about_z(30))) == std::vector<double>{0});
    reduce_options exact;
    exact.tol_deg = 0;
    CHECK(kept_times({about_z(0), about_z(0), about_z(0), about_z(90), about_z(90), about_z(90)}, exact) ==
          std::vector<double>{0, 2, 3, 5});
    // -q is q: a sign flip is no change.
    CHECK(kept_times({about_z(0), -about_z(0), about_z(0)}, exact) == std::vector<double>{0});
}

TEST_CASE("reduce: step keeps the key where each value begins, and the last") {
    reduce_options step;
    step.how = method::step;
    // Held from key 0 through key 1, from key 2 through key 4; key 5 last.
    CHECK(kept_times({about_z(0), about_z(0), about_z(40), about_z(40), about_z(40), about_z(80)}, step) ==
          std::vector<double>{0, 2, 5});
}

TEST_CASE("reduce: translations count against --tol-translation") {
    const std::vector<quat> still(5, quat{});
    // Linear but for the middle key, 0.002 off: out of the default 0.001.
    const std::vector<std::optional<vec3>> moves{vec3{0, 0, 0}, vec3{1, 0, 0}, vec3{2, 0.002, 0}, vec3{3, 0, 0},
                                                 vec3{4, 0, 0}};
    CHECK(kept_times(still, {}, moves) == std::vector<double>{0, 2, 4});
    reduce_options loose;
    loose.tol_translation = 0.01;
    CHECK(kept_times(still, loose, moves) == std::vector<double>{0, 4});
}
