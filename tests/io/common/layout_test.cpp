#include "io/common/layout.hpp"

#include <doctest/doctest.h>
#include <cmath>
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
