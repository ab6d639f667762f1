// SPDX-License-Identifier: MIT
#include "io/common/layout.hpp"

#include <doctest/doctest.h>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>


using namespace keyrot;

TEST_CASE("append_number appends what the number writer writes") {
    std::string s = "x=";
    append_number(s, 0.1 + 0.2, std::nullopt);
    CHECK(s == "x=0.30000000000000004");
    append_number(s, -2.50, 3);
    CHECK(s == "x=0.30000000000000004-2.5");
}

TEST_CASE("CSV columns per representation and quaternion order") {
    const auto q = rotation_columns(rep::quat, quat_order::xyzw);
    CHECK(std::vector<std::string_view>(q.begin(), q.end()) == std::vector<std::string_view>{"qx", "qy", "qz", "qw"});
    CHECK(rotation_columns(rep::axis_angle, quat_order::wxyz).back() == "angle");
    CHECK(rotation_columns(rep::matrix, quat_order::wxyz).size() == 9);
    CHECK(rotation_columns(rep::matrix4, quat_order::wxyz).size() == 16);
    CHECK(from_quat_order({1, 2, 3, 4}, quat_order::xyzw) == std::array<double, 4>{4, 1, 2, 3});
}

TEST_CASE("values of a rotation in each representation and unit") {
    const double s = std::sqrt(0.5);
    const quat q{s, 0, 0, s};  // 90 degrees about z
    write_options o;
    o.representation = rep::axis_angle;
    auto v = values_of(q, std::nullopt, o);
    CHECK(v.size == 4);
    CHECK(std::fabs(v.v[3] - 90) <= 2e-14);
    o.angles = angle_unit::radians;
    v = values_of(q, std::nullopt, o);
    CHECK(std::fabs(v.v[3] - std::numbers::pi / 2) <= 4e-16);
    o.representation = rep::quat;
    o.order = quat_order::xyzw;
    v = values_of(q, std::nullopt, o);
    CHECK(v.v[3] == s);
    o.representation = rep::matrix4;
    v = values_of(q, vec3{1, 2, 3}, o);
    CHECK(v.size == 16);
    CHECK(v.v[3] == 1);
    CHECK(v.v[7] == 2);
    CHECK(v.v[11] == 3);
    CHECK(v.v[15] == 1);
    CHECK(std::fabs(v.v[1] + 1) <= 1e-15);  // m01 = -sin 90
}

TEST_CASE("sign_free: a representation's values are q's and -q's bit for bit") {
    // resample hands squad frames to the formatting threads, unsigned, only for these.
    std::vector<quat> qs = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 0, 1}, {-0.0, 0.6, 0, 0.8}, {0.0, -0.6, 0.8, 0},
                            {std::sqrt(0.5), 0, 0, -std::sqrt(0.5)}};
    std::uint64_t state = 12345;
    const auto uniform = [&state] {  // (a fixed generator: the same quaternions everywhere)
        state = state * 6364136223846793005u + 1442695040888963407u;
        return static_cast<double>(state >> 11) * 0x1p-53 * 2 - 1;
    };
    for (int i = 0; i < 20000; ++i) qs.push_back(normalized(quat{uniform(), uniform(), uniform(), uniform()}));
    const auto bits = [](const rotation_values& r) {
        std::vector<std::uint64_t> b;
        for (std::size_t i = 0; i < r.size; ++i) b.push_back(std::bit_cast<std::uint64_t>(r.v[i]));
        return b;
    };
    for (const rep r : {rep::axis_angle, rep::rotvec, rep::matrix, rep::matrix4, rep::quat, rep::euler}) {
        write_options o;
        o.representation = r;
        o.euler = parse_euler_seq("ZYX");
        std::size_t same = 0;
        for (const quat& q : qs) same += bits(values_of(q, std::nullopt, o)) == bits(values_of(-q, std::nullopt, o));
        CAPTURE(to_string(r));
        if (sign_free(o)) {
            CHECK(same == qs.size());
        } else {
            CHECK(same < qs.size());
        }
    }
}
