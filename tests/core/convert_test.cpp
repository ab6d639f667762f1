// SPDX-License-Identifier: MIT
#include "keyrot/convert.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "helpers.hpp"

using namespace keyrot;
using keyrot::test::max_diff;
using keyrot::test::near;
using keyrot::test::same_rotation;

namespace {

constexpr double pi = std::numbers::pi;
const std::array<const char*, 12> sequences = {"XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX",
                                               "XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ"};

/// Elementary rotation matrices written out, independent of the quaternion code.
mat3 elementary_matrix(int axis, double a) {
    const double c = std::cos(a), s = std::sin(a);
    mat3 r;
    if (axis == 0) r.m = {{{1, 0, 0}, {0, c, -s}, {0, s, c}}};
    if (axis == 1) r.m = {{{c, 0, s}, {0, 1, 0}, {-s, 0, c}}};
    if (axis == 2) r.m = {{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
    return r;
}

mat3 multiply(const mat3& a, const mat3& b) {
    mat3 r;
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j)
            for (std::size_t k = 0; k < 3; ++k) r.m[i][j] += a.m[i][k] * b.m[k][j];
    return r;
}

double matrix_diff(const mat3& a, const mat3& b) {
    double d = 0;
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j) d = std::fmax(d, std::fabs(a.m[i][j] - b.m[i][j]));
    return d;
}

euler_seq seq(const char* name) { return *parse_euler_seq(name); }

}  // namespace

TEST_CASE("names of representations, units and sequences") {
    for (const auto& [value, name] : names_of<rep>) {
        CHECK(parse<rep>(name) == value);
        CHECK(to_string(value) == name);
    }
    CHECK(parse<rep>("axis-angle") == rep::axis_angle);  // the spec's names, written out
    CHECK(to_string(rep::matrix4) == "matrix4");
    CHECK(to_string(quat_order::xyzw) == "xyzw");
    CHECK_FALSE(parse<rep>("quaternion"));
    CHECK(parse<angle_unit>("radians") == angle_unit::radians);
    CHECK_FALSE(parse<angle_unit>("deg"));
    CHECK(seq("ZYX").intrinsic);
    CHECK_FALSE(seq("zyx").intrinsic);
    CHECK(seq("zyx").axes == std::array<int, 3>{2, 1, 0});
    for (const char* bad : {"", "XY", "XYZX", "XXY", "XyZ", "abc", "XYY", "xxz"}) {
        CAPTURE(bad);
        CHECK_FALSE(parse_euler_seq(bad));
    }
}

TEST_CASE("90 degrees about z, derived by hand") {
    const double s = std::sqrt(0.5);
    const quat q = from_axis_angle({0, 0, 5}, pi / 2);  // axis need not be unit
    CHECK(max_diff(q, quat{s, 0, 0, s}) <= 1.2e-16);  // one ulp
    // The spec: R = [[cos, -sin, 0], [sin, cos, 0], [0, 0, 1]]
    CHECK(matrix_diff(to_matrix(q), elementary_matrix(2, pi / 2)) <= 1e-15);
    const axis_angle aa = to_axis_angle(q);
    CHECK(near(aa.angle, pi / 2, 2e-16));
    CHECK(aa.axis.z == 1);
    const vec3 rv = to_rotvec(q);
    CHECK(near(rv.z, pi / 2, 2e-16));
    CHECK(max_diff(from_rotvec({0, 0, pi / 2}), q) <= 1e-16);
}

TEST_CASE("identity: axis (1, 0, 0), angle 0") {
    const axis_angle aa = to_axis_angle(quat{});
    CHECK(aa.angle == 0);
    CHECK(aa.axis.x == 1);
    CHECK(to_axis_angle(quat{-1, 0, 0, 0}).angle == 0);
    CHECK(max_diff(from_rotvec({0, 0, 0}), quat{}) == 0);
}

TEST_CASE("180 degree cases: angle pi, axis independent of the sign of q") {
    for (vec3 axis : {vec3{1, 0, 0}, vec3{0, -1, 0}, vec3{0, 0, 1}, vec3{-0.6, 0.8, 0}}) {
        const quat q{0, axis.x, axis.y, axis.z};
        const axis_angle a = to_axis_angle(q), b = to_axis_angle(-q);
        CHECK(a.angle == pi);
        CHECK(a.axis.x == b.axis.x);
        CHECK(a.axis.y == b.axis.y);
        CHECK(a.axis.z == b.axis.z);
        const double first = a.axis.x != 0 ? a.axis.x : a.axis.y != 0 ? a.axis.y : a.axis.z;
        CHECK(first > 0);
    }
    // 180 about x: diag(1, -1, -1)
    const mat3 m = to_matrix(quat{0, 1, 0, 0});
    CHECK(matrix_diff(m, elementary_matrix(0, pi)) <= 1e-15);
}

TEST_CASE("w < 0 gives the same axis-angle as w > 0") {
    keyrot::test::random_rotations rng(11);
    for (int n = 0; n < 50; ++n) {
        quat q = rng.next();
        if (q.w > 0) q = -q;
        const axis_angle a = to_axis_angle(q), b = to_axis_angle(-q);
        CHECK(a.angle == b.angle);
        CHECK((a.axis.x == b.axis.x && a.axis.y == b.axis.y && a.axis.z == b.axis.z));
        CHECK(a.angle <= pi);
        CHECK(same_rotation(from_axis_angle(a.axis, a.angle), q, 1e-15));
    }
}

TEST_CASE("Euler: intrinsic XYZ is Rx(a) Ry(b) Rz(c), extrinsic xyz is Rz(c) Ry(b) Rx(a)") {
    const std::array<double, 3> e = {0.3, -1.1, 2.5};
    for (const char* name : sequences) {
        CAPTURE(name);
        const euler_seq s = seq(name);
        const mat3 a = elementary_matrix(s.axes[0], e[0]), b = elementary_matrix(s.axes[1], e[1]),
                   c = elementary_matrix(s.axes[2], e[2]);
        CHECK(matrix_diff(to_matrix(from_euler(e, s)), multiply(multiply(a, b), c)) <= 1e-15);
        std::string lower(name);
        for (char& ch : lower) ch = static_cast<char>(ch - 'A' + 'a');
        CHECK(matrix_diff(to_matrix(from_euler(e, seq(lower.c_str()))), multiply(multiply(c, b), a)) <= 1e-15);
    }
}

TEST_CASE("Euler: XYZ with (a, b, c) equals zyx with (c, b, a)") {
    const quat p = from_euler({0.1, 0.2, 0.3}, seq("XYZ"));
    const quat q = from_euler({0.3, 0.2, 0.1}, seq("zyx"));
    CHECK(max_diff(p, q) <= 1e-16);
}

TEST_CASE("Euler round trip in all 24 sequences, within scipy's canonical ranges") {
    keyrot::test::random_rotations rng(24);
    for (const char* upper : sequences) {
        for (bool intrinsic : {true, false}) {
            std::string name(upper);
            if (!intrinsic)
                for (char& ch : name) ch = static_cast<char>(ch - 'A' + 'a');
            CAPTURE(name);
            const euler_seq s = seq(name.c_str());
            const bool proper = s.axes[0] == s.axes[2];
            for (int n = 0; n < 200; ++n) {
                const quat q = rng.next();
                const euler_angles e = to_euler(q, s);
                CHECK_FALSE(e.gimbal_lock);
                CHECK(std::fabs(e.angles[0]) <= pi);
                CHECK(std::fabs(e.angles[2]) <= pi);
                if (proper) CHECK((e.angles[1] >= 0 && e.angles[1] <= pi));
                else CHECK(std::fabs(e.angles[1]) <= pi / 2);
                CHECK(same_rotation(from_euler(e.angles, s), q, 1e-15));
            }
        }
    }
}

TEST_CASE("Euler angles of a hand-made rotation come back as given") {
    // yaw 30, pitch 20, roll 10 degrees, intrinsic ZYX
    const std::array<double, 3> e = {pi / 6, pi / 9, pi / 18};
    const euler_angles back = to_euler(from_euler(e, seq("ZYX")), seq("ZYX"));
    for (std::size_t i = 0; i < 3; ++i) CHECK(near(back.angles[i], e[i], 1e-15));
}

TEST_CASE("gimbal lock: the third angle is 0 and the rotation is kept") {
    for (const char* name : {"ZYX", "xyz", "ZXZ", "yxy"}) {
        CAPTURE(name);
        const euler_seq s = seq(name);
        const bool proper = s.axes[0] == s.axes[2];
        for (double middle : proper ? std::array<double, 2>{0, pi} : std::array<double, 2>{pi / 2, -pi / 2}) {
            const quat q = from_euler({0.4, middle, 0.7}, s);
            const euler_angles e = to_euler(q, s);
            CHECK(e.gimbal_lock);
            CHECK(e.angles[2] == 0);
            CHECK(same_rotation(from_euler(e.angles, s), q, 1e-15));
        }
    }
}

TEST_CASE("gimbal lock: a middle angle within 4e-16 rad of 0 or pi, and none further away") {
    // ZXZ with the middle turn about x written exactly: delta/2 is its own
    // sine and 1 its cosine, so delta from 0 is (1, delta/2, 0, 0) and
    // delta from pi is (delta/2, 1, 0, 0).
    const quat outer = from_axis_angle({0, 0, 1}, 0.4), inner = from_axis_angle({0, 0, 1}, 0.7);
    for (bool from_pi : {false, true}) {
        for (double delta : {0.0, 1e-16, 2e-16, 3.5e-16, 5e-16, 1e-15, 3e-15, 1e-12}) {
            CAPTURE(from_pi);
            CAPTURE(delta);
            const quat middle = from_pi ? quat{delta / 2, 1, 0, 0} : quat{1, delta / 2, 0, 0};
            const quat q = outer * middle * inner;
            const euler_angles e = to_euler(q, seq("ZXZ"));
            CHECK(e.gimbal_lock == (delta <= 3.5e-16));
            CHECK((e.angles[2] == 0) == e.gimbal_lock);
            CHECK(same_rotation(from_euler(e.angles, seq("ZXZ")), q, 1e-15));
        }
    }
}

TEST_CASE("matrix round trip through every Shepperd branch, near 0 and 180 degrees") {
    keyrot::test::random_rotations rng(9);
    std::vector<quat> fixtures = {quat{}, quat{0, 1, 0, 0}, quat{0, 0, 1, 0}, quat{0, 0, 0, 1},
                                  from_axis_angle({1, 2, 3}, 1e-9), from_axis_angle({1, 2, 3}, pi - 1e-9),
                                  from_axis_angle({-3, 1, 2}, pi)};
    for (int n = 0; n < 200; ++n) fixtures.push_back(rng.next());
    for (const quat& q : fixtures) {
        CAPTURE(q.w);
        CHECK(same_rotation(from_matrix(to_matrix(q)), q, 4e-16));
    }
}

TEST_CASE("matrix built by hand from elementary rotations converts to the same quaternion") {
    const mat3 m = multiply(elementary_matrix(2, 0.7), elementary_matrix(0, -0.2));
    const quat q = from_axis_angle({0, 0, 1}, 0.7) * from_axis_angle({1, 0, 0}, -0.2);
    CHECK(same_rotation(from_matrix(m), q, 1e-15));
}

TEST_CASE("tiny angles keep their relative precision") {
    for (double angle : {1e-100, 1e-30, 1e-10}) {
        CAPTURE(angle);
        const quat q = from_axis_angle({0, 1, 0}, angle);
        CHECK(near(to_axis_angle(q).angle, angle, 1e-15 * angle));
        CHECK(near(to_rotvec(q).y, angle, 1e-15 * angle));
    }
}

TEST_CASE("degree inputs: whole quarter turns are exact") {
    const double s = std::sqrt(0.5);
    const quat q90 = from_axis_angle({0, 0, 1}, 90, angle_unit::degrees);
    CHECK(q90.w == s);
    CHECK(q90.z == s);
    const axis_angle full = to_axis_angle(from_axis_angle({0, 0, 1}, 360, angle_unit::degrees));
    CHECK(full.angle == 0);  // exactly the identity, not 2e-16 about -z
    CHECK(full.axis.x == 1);
    const quat half_turn = from_rotvec({0, 180, 0}, angle_unit::degrees);
    CHECK(half_turn.w == 0);
    CHECK(half_turn.y == 1);
    const quat e = from_euler({90, -90, 180}, seq("ZYX"), angle_unit::degrees);
    const quat by_hand = from_euler({pi / 2, -pi / 2, pi}, seq("ZYX"));
    CHECK(same_rotation(e, by_hand, 4e-16));  // the radian version carries the rounding of pi/4
    CHECK(from_radians(pi, angle_unit::degrees) == 180);
    CHECK(to_radians(180, angle_unit::degrees) == pi);
    CHECK(from_radians(pi / 2, angle_unit::degrees) == 90);
    CHECK(to_axis_angle(q90).axis.z == 1);
}

TEST_CASE("components whose length overflows or is subnormal still give the unit rotation") {
    // A quaternion of four 1.7e308s is (1, 1, 1, 1) / 2; one of the smallest
    // subnormals twice (its length rounds to one of them) is (1, 1, 0, 0) / sqrt(2).
    const double s = std::sqrt(0.5);
    CHECK(max_diff(normalized({1.7e308, 1.7e308, 1.7e308, 1.7e308}), {0.5, 0.5, 0.5, 0.5}) <= 2.3e-16);
    CHECK(max_diff(normalized({5e-324, 5e-324, 0, 0}), {s, s, 0, 0}) <= 2.3e-16);
    // 90 degrees about an axis whose length overflows: about (1, 1, 1); or is
    // subnormal: about x, and about (1, 1, 0).
    const quat about_diagonal = from_axis_angle({1.7e308, 1.7e308, 1.7e308}, 90, angle_unit::degrees);
    CHECK(max_diff(about_diagonal, {s, s / std::sqrt(3.0), s / std::sqrt(3.0), s / std::sqrt(3.0)}) <= 2.3e-16);
    CHECK(max_diff(from_axis_angle({1e-320, 0, 0}, 90, angle_unit::degrees), {s, s, 0, 0}) <= 2.3e-16);
    CHECK(max_diff(from_axis_angle({5e-324, 5e-324, 0}, 90, angle_unit::degrees), {s, 0.5, 0.5, 0}) <= 2.3e-16);
    // Rotation vectors too long for the squares of their components: the
    // half angle reduced exactly (1e200 / 2 is 64 degrees past a whole
    // number of turns: Python's Fraction), a unit quaternion about the
    // vector's direction.
    const quat z = from_rotvec({0, 0, 1e200}, angle_unit::degrees);
    CHECK(max_diff(z, {std::cos(64 * pi / 180), 0, 0, std::sin(64 * pi / 180)}) <= 4e-16);
    for (const vec3 v : {vec3{1.7e308, 1.7e308, 1.7e308}, vec3{1, 5.5e174, 0}, vec3{0, -1e150, 0}}) {
        for (const angle_unit unit : {angle_unit::degrees, angle_unit::radians}) {
            CAPTURE(v.y);
            const quat r = from_rotvec(v, unit);
            CHECK(near(norm(r), 1, 4e-16));
            const double largest = std::fmax(std::fabs(v.x), std::fmax(std::fabs(v.y), std::fabs(v.z)));
            const vec3 direction = (1 / largest) * v;
            CHECK(norm(cross(vector_part(r), (1 / norm(direction)) * direction)) <= 4e-16);
        }
    }
}

TEST_CASE("rotation vectors of every length give unit quaternions about their direction") {
    // Past a few million the length's rounding error is more than a
    // millionth of a radian, so it cannot be corrected to first order; the
    // first (fuzz) vector, 5.6e21 long, once gave a quaternion of length 700.
    for (const vec3 direction : {vec3{1, 5.5555555555555500000004e21, 5.5555555555555e18}, vec3{3, -4, 12}}) {
        const vec3 unit_direction = (1 / norm(direction)) * direction;
        for (int e = 0; e <= 300; ++e) {
            for (const angle_unit unit : {angle_unit::degrees, angle_unit::radians}) {
                CAPTURE(e);
                const quat r = from_rotvec(std::pow(10.0, e) * unit_direction, unit);
                CHECK(near(norm(r), 1, 4e-16));
                CHECK(norm(cross(vector_part(r), unit_direction)) <= 4e-16);
            }
        }
    }
}

namespace {

/// The largest difference between two angle triples.
double max_angle_diff(const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::max({std::fabs(a[0] - b[0]), std::fabs(a[1] - b[1]), std::fabs(a[2] - b[2])});
}

}  // namespace

TEST_CASE("continuous_euler: the same rotation, the triple nearest the previous one") {
    // 179 then 181 degrees about z (ZYX): canonical -179, continuous 181.
    const euler_seq zyx = *parse_euler_seq("ZYX");
    const auto next = continuous_euler(from_euler({181, 0, 0}, zyx, angle_unit::degrees), zyx, {179 * pi / 180, 0, 0}).angles;
    CHECK(to_euler(from_euler({181, 0, 0}, zyx, angle_unit::degrees), zyx).angles[0] < 0);
    CHECK(near(next[0], 181 * pi / 180, 1e-14));
    // Two turns on: whole turns are added, not only one.
    CHECK(near(continuous_euler(quat{}, zyx, {4 * pi + 0.1, 0, 0}).angles[0], 4 * pi, 1e-14));
    // The other Tait-Bryan solution where it is nearer: (10, 100, 20) is canonically (-170, 80, -160).
    const quat past = from_euler({10, 100, 20}, zyx, angle_unit::degrees);
    const auto other = continuous_euler(past, zyx, {10 * pi / 180, 99 * pi / 180, 20 * pi / 180}).angles;
    CHECK(max_angle_diff(other, {10 * pi / 180, 100 * pi / 180, 20 * pi / 180}) < 1e-13);
    // Proper Euler: (a + 180, -b, c + 180).
    const euler_seq zxz = *parse_euler_seq("ZXZ");
    const quat q = from_euler({30, -20, 40}, zxz, angle_unit::degrees);
    CHECK(max_angle_diff(continuous_euler(q, zxz, {0.5, -0.3, 0.7}).angles, {30 * pi / 180, -20 * pi / 180, 40 * pi / 180}) < 1e-13);
    // Any rotation, any previous triple, every sequence: the same rotation, each angle within
    // half a turn of the previous one.
    for (const char* name : sequences) {
        const euler_seq seq = *parse_euler_seq(name);
        for (int i = 0; i < 200; ++i) {
            const quat r = normalized(quat{std::sin(i * 1.3), std::cos(i * 0.7), std::sin(i * 2.1 + 1), std::cos(i * 0.3)});
            const std::array<double, 3> before = {std::sin(i * 0.9) * 20, std::cos(i * 1.7) * 3, std::sin(i * 0.4) * 9};
            const auto e = continuous_euler(r, seq, before).angles;
            CHECK(same_rotation(from_euler(e, seq), r, 1e-12));
            for (std::size_t k = 0; k < 3; ++k) CHECK(std::fabs(e[k] - before[k]) <= pi + 1e-12);
        }
    }
    // At gimbal lock, as to_euler says it
    CHECK(continuous_euler(from_euler({10, 90, 0}, zyx, angle_unit::degrees), zyx, {0, 1.5, 0}).gimbal_lock);
    CHECK(!continuous_euler(from_euler({10, 80, 0}, zyx, angle_unit::degrees), zyx, {0, 1.5, 0}).gimbal_lock);
}
