#include "keyrot/layout.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

using namespace keyrot;

namespace {
std::string number(double v, std::optional<int> precision = std::nullopt) {
    std::string s;
    append_number(s, v, precision);
    return s;
}
}  // namespace

TEST_CASE("numbers print in the shortest form that reads back") {
    CHECK(number(0) == "0");
    CHECK(number(-0.0) == "0");
    CHECK(number(1) == "1");
    CHECK(number(0.1) == "0.1");
    CHECK(number(1.0 / 3) == "0.3333333333333333");
    CHECK(number(0.1 + 0.2) == "0.30000000000000004");
    CHECK(number(-2.5e-300) == "-2.5e-300");
    for (double v : {std::numbers::pi, 1.0 / 7, 1e-17, 123456.789, -0.7071067811865476}) {
        CAPTURE(v);
        CHECK(std::stod(number(v)) == v);
    }
}

TEST_CASE("the shortest form is laid out exactly as fmt's \"{}\"") {
    // keyrot writes the shortest digits itself; fmt's general formatter is
    // the independent reference for the layout (fixed within 1e-4..1e16,
    // exponents with a sign and at least two digits).
    const auto same_as_fmt = [](double v) {
        CAPTURE(v);
        REQUIRE(number(v) == fmt::format("{}", v));
    };
    for (double v : {1e-5, 1.5e-5, 1e-4, 0.000123, 1e15, 1.5e15, 9999999999999998.0, 1e16, 1.25e16, 1e17, 1e100,
                     1.2345e-100, 5e-324, 2.2250738585072014e-308, 1.7976931348623157e308, 0.1, 123.456, -0.5})
        same_as_fmt(v);
    for (double p = 1; p < 1e18; p *= 10)  // whole numbers: the integer path up to 1e15
        for (double v : {p - 1, p, p + 1, -p, 1 - p}) same_as_fmt(v);
    for (double v = 0; v < 1e8; v += 997) {  // every digit in every place of both 8-digit halves
        same_as_fmt(v);
        same_as_fmt(v * 1e7 + (1e8 - 1 - v));
    }
    std::mt19937_64 gen(11);
    std::uniform_int_distribution<std::uint64_t> bits;
    std::uniform_real_distribution<double> unit(-1, 1), exponent(-30, 30);
    for (int i = 0; i < 200000; ++i) {
        const double any = std::bit_cast<double>(bits(gen));  // every binary exponent
        if (std::isfinite(any) && any != 0) same_as_fmt(any);
        same_as_fmt(unit(gen));                                 // quaternion and axis components
        same_as_fmt(unit(gen) * std::pow(10.0, exponent(gen)));  // every decimal layout
        same_as_fmt(static_cast<double>(i) / 24);               // frame times
        same_as_fmt(std::trunc(unit(gen) * std::pow(10.0, exponent(gen) / 2)) + 0.0);  // whole numbers (+ 0.0: not -0)
    }
}

TEST_CASE("--precision rounds and drops trailing zeros, never -0") {
    CHECK(number(0.38268343236508978, 4) == "0.3827");
    CHECK(number(0.5, 4) == "0.5");
    CHECK(number(0, 4) == "0");
    CHECK(number(-0.00001, 4) == "0");
    CHECK(number(-0.0, 2) == "0");
    CHECK(number(2.0, 0) == "2");
    CHECK(number(-1.25, 1) == "-1.2");  // round half to even on the binary value
    CHECK(number(123.0, 3) == "123");
    const std::string longest = number(-1.7976931348623157e308, 17);  // the widest number there is
    CHECK(longest.size() == 1 + 309);
    CHECK(longest.size() <= max_number_chars);
    CHECK(std::stod(longest) == -1.7976931348623157e308);
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

TEST_CASE("parse_number reads finite doubles only") {
    CHECK(parse_number(" 1.5 ") == 1.5);
    CHECK(parse_number("+2") == 2);
    CHECK(parse_number("-1e-3") == -1e-3);
    for (const char* bad : {"", "abc", "1.5x", "nan", "inf", "-inf", "1e400", "++1", "1 2", "0x10"}) {
        CAPTURE(bad);
        CHECK_FALSE(parse_number(bad));
    }
}

TEST_CASE("UTF-8 validation") {
    CHECK(is_valid_utf8("hip"));
    CHECK(is_valid_utf8("h\xC3\xBC" "fte"));  // hüfte
    CHECK_FALSE(is_valid_utf8("\xFF"));
    CHECK_FALSE(is_valid_utf8("\xC3"));
    CHECK_FALSE(is_valid_utf8("\xC0\xAF"));          // overlong
    CHECK_FALSE(is_valid_utf8("\xED\xA0\x80"));      // surrogate
}
