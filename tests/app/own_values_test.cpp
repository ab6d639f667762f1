// SPDX-License-Identifier: MIT
// The values a row writes of its own: the input's numbers at its keys,
// Euler angles on the input's branch between them.
#include "app/own_values.hpp"

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <vector>

#include "helpers.hpp"
#include "keyrot/interpolate.hpp"

using namespace keyrot;
using namespace keyrot::detail;

namespace {

/// A key at `time` given as `values` of kind `as` (degrees), its rotation
/// as keyrot reads them (Euler angles in `seq`).
key given_key(double time, rep as, std::array<double, 4> values, const euler_seq& seq = *parse_euler_seq("ZYX")) {
    key k = test::key_at(time, quat{});
    k.given_as = as;
    k.given = given_rotation{values, angle_unit::degrees};
    const auto& v = values;
    switch (as) {
        case rep::quat: k.rotation = normalized(quat{v[0], v[1], v[2], v[3]}); break;
        case rep::axis_angle: k.rotation = from_axis_angle({v[0], v[1], v[2]}, v[3], angle_unit::degrees); break;
        case rep::rotvec: k.rotation = from_rotvec({v[0], v[1], v[2]}, angle_unit::degrees); break;
        default: k.rotation = from_euler({v[0], v[1], v[2]}, seq, angle_unit::degrees); break;
    }
    return k;
}

write_options output(rep r, const std::optional<euler_seq>& seq = std::nullopt) {
    write_options w;
    w.representation = r;
    w.euler = seq;
    return w;
}

/// The values (the first `n`) written of each key, a row a key, or none.
std::vector<std::optional<std::vector<double>>> written(own_values& own, const std::vector<key>& keys, std::size_t n,
                                                         const std::optional<euler_seq>& seq = std::nullopt) {
    own.begin_track(seq, method::slerp, std::nullopt);
    std::vector<std::optional<std::vector<double>>> out;
    for (const key& k : keys) {
        own.key(k);
        const own_rotation* r = own.of(k.time, k.rotation);
        out.push_back(r ? std::optional(std::vector<double>(r->values.begin(), r->values.begin() + n)) : std::nullopt);
    }
    return out;
}

}  // namespace

TEST_CASE("own values: each key in its own representation, written with the numbers it was given") {
    SUBCASE("quaternions of unit length but for rounding, as given; others left to the writer") {
        own_values own(output(rep::quat), format::csv);
        const auto w = written(own, {given_key(0, rep::quat, {0.9238795325112867, 0, 0, 0.3826834323650898}),
                                     given_key(1, rep::quat, {0.7071, 0, 0, 0.7071}), given_key(2, rep::quat, {0.5, 0.5, 0.5, 0.5})},
                               4);
        CHECK(w[0] == std::vector<double>{0.9238795325112867, 0, 0, 0.3826834323650898});
        CHECK(!w[1]);  // norm 0.99999: normalised, as read
        CHECK(w[2] == std::vector<double>{0.5, 0.5, 0.5, 0.5});
        // a row at -q: -given
        own.begin_track(std::nullopt, method::slerp, std::nullopt);
        const key k = given_key(0, rep::quat, {0.5, 0.5, 0.5, 0.5});
        own.key(k);
        CHECK(own.of(0, -k.rotation)->values == std::array<double, 4>{-0.5, -0.5, -0.5, -0.5});
    }
    SUBCASE("axis and angle made canonical by steps that round nothing") {
        own_values own(output(rep::axis_angle), format::csv);
        const auto w = written(own, {given_key(0, rep::axis_angle, {0, 0, 1, 45}), given_key(1, rep::axis_angle, {0, 0, 1, -30.5}),
                                     given_key(2, rep::axis_angle, {0, 1, 0, 270.25}), given_key(3, rep::axis_angle, {0, 0, 2, 17.3}),
                                     given_key(4, rep::axis_angle, {0, -1, 0, 180}), given_key(5, rep::axis_angle, {0, 0, 1, 0}),
                                     given_key(6, rep::axis_angle, {0, 0, 1, 725}), given_key(7, rep::axis_angle, {1, 1, 1, 10})},
                               4);
        CHECK(w[0] == std::vector<double>{0, 0, 1, 45});
        CHECK(w[1] == std::vector<double>{-0.0, -0.0, -1, 30.5});
        CHECK(w[2] == std::vector<double>{-0.0, -1, -0.0, 89.75});
        CHECK(w[3] == std::vector<double>{0, 0, 1, 17.3});
        CHECK(w[4] == std::vector<double>{-0.0, 1, -0.0, 180});
        CHECK(w[5] == std::vector<double>{1, 0, 0, 0});
        CHECK(!w[6]);  // past a turn: the writer's
        // divided by its length to the nearest double: 1/sqrt(3) is 0.57735026918962576451, nearer
        // 0.5773502691896257 (3.3e-17 off) than 0.5773502691896258 (7.8e-17; Python's decimal module)
        CHECK(w[7] == std::vector<double>{0.5773502691896257, 0.5773502691896257, 0.5773502691896257, 10});
    }
    SUBCASE("rotation vectors up to half a turn long") {
        own_values own(output(rep::rotvec), format::csv);
        const auto w = written(own, {given_key(0, rep::rotvec, {10, 20, 30}), given_key(1, rep::rotvec, {0, 0, -180}),
                                     given_key(2, rep::rotvec, {0, 0, 190})},
                               3);
        CHECK(w[0] == std::vector<double>{10, 20, 30});
        CHECK(w[1] == std::vector<double>{-0.0, -0.0, 180});
        CHECK(!w[2]);
    }
    SUBCASE("only in the representation given, and never for matrices or glTF") {
        own_values own(output(rep::axis_angle), format::csv);
        CHECK(!written(own, {given_key(0, rep::quat, {1, 0, 0, 0})}, 4)[0]);
        CHECK(!own_values(output(rep::matrix), format::csv).any());
        CHECK(!own_values(output(rep::quat), format::glb).any());
    }
    SUBCASE("in the output's unit") {
        write_options w = output(rep::rotvec);
        w.angles = angle_unit::radians;
        own_values own(w, format::csv);
        const auto v = written(own, {given_key(0, rep::rotvec, {0, 0, 90})}, 3);
        CHECK(v[0] == std::vector<double>{0, 0, to_radians(90, angle_unit::degrees)});
    }
}

TEST_CASE("own values: Euler angles on the input's own branch between its keys") {
    const euler_seq zyx = *parse_euler_seq("ZYX");
    // About z: 3.29, a frame flipped half a turn, 3.29 again, 5.29, then 179 and past +-180 as a capture writes it.
    const std::vector<key> keys = {given_key(0, rep::euler, {3.29, 0, 0}), given_key(1, rep::euler, {-176.71, 0, 0}),
                                   given_key(2, rep::euler, {3.29, 0, 0}),  given_key(3, rep::euler, {5.29, 0, 0}),
                                   given_key(4, rep::euler, {179, 0, 0}),   given_key(5, rep::euler, {-179, 0, 0})};
    own_values own(output(rep::euler, zyx), format::csv);
    own.begin_track(zyx, method::slerp, 4);
    std::vector<double> first;  // the first angle of each row slerp makes at 4 fps
    own.key(keys[0]);
    for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
        own.key(keys[i + 1]);  // (each key comes before the rows of the segment it ends)
        const quat q0 = keys[i].rotation, q1 = dot(q0, keys[i + 1].rotation) < 0 ? -keys[i + 1].rotation : keys[i + 1].rotation;
        for (int j = 0; j < 4; ++j)
            first.push_back(own.of(static_cast<double>(i) + j / 4.0, j == 0 ? q0 : slerp(q0, q1, j / 4.0))->values[0]);
    }
    first.push_back(own.of(5, keys.back().rotation)->values[0]);
    REQUIRE(first.size() == 21);
    // At the keys, their own numbers
    for (std::size_t i = 0; i < keys.size(); ++i) CHECK(first[4 * i] == keys[i].given->values[0]);
    // After the flip's segments, the take's angles again (3.79, 4.29, 4.79), not a turn off
    for (std::size_t f = 9; f < 12; ++f) CHECK(std::fabs(first[f] - (3.29 + 0.5 * static_cast<double>(f - 8))) < 1e-9);
    // Past +-180 between 179 and -179, going on from the key before: 179.5, 180, 180.5
    CHECK(std::fabs(first[17] - 179.5) < 1e-9);
    CHECK(std::fabs(first[18] - 180) < 1e-9);
    CHECK(std::fabs(first[19] - 180.5) < 1e-9);
}

TEST_CASE("own values: --method euler's rows, linear in the keys' own numbers; other sequences continuous or canonical") {
    const euler_seq zyx = *parse_euler_seq("ZYX"), xyz = *parse_euler_seq("xyz");
    own_values own(output(rep::euler, zyx), format::csv);
    own.begin_track(zyx, method::euler, 4);
    const key a = given_key(0, rep::euler, {170, 0, 0}), b = given_key(1, rep::euler, {190, 10, 0});
    own.key(a), own.key(b);
    own.of(0, a.rotation);
    const quat half = from_euler({180, 5, 0}, zyx, angle_unit::degrees);
    CHECK(own.of(0.5, half)->values == std::array<double, 4>{180, 5, 0, 0});
    // keys in another sequence than the output's: the writer's canonical angles, or continuous when asked
    own_values canonical(output(rep::euler, xyz), format::csv);
    canonical.begin_track(zyx, method::slerp, std::nullopt);
    canonical.key(a);
    CHECK(!canonical.of(0, a.rotation));
    write_options w = output(rep::euler, xyz);
    w.euler_continuous = true;
    own_values continuous(w, format::csv);
    continuous.begin_track(zyx, method::slerp, std::nullopt);
    double previous = 0;
    for (int d = 170; d <= 200; d += 10) {
        const quat q = from_euler({0, 0, static_cast<double>(d)}, xyz, angle_unit::degrees);
        const double z = continuous.of(d, q)->values[2];
        if (d > 170) CHECK(std::fabs(z - previous - 10) < 1e-9);
        previous = z;
    }
    // BVH: each track's own sequence, in degrees whatever the flags, continuous
    w.angles = angle_unit::radians;
    own_values bvh(w, format::bvh);
    bvh.begin_track(zyx, method::slerp, std::nullopt);
    bvh.key(a);
    CHECK(bvh.of(0, a.rotation)->values == std::array<double, 4>{170, 0, 0, 0});
}
