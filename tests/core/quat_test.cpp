// SPDX-License-Identifier: MIT
#include "keyrot/quat.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "helpers.hpp"

using namespace keyrot;
using keyrot::test::max_diff;
using keyrot::test::near;

TEST_CASE("Hamilton's product: ij = k, jk = i, ki = j, i^2 = -1") {
    const quat i{0, 1, 0, 0}, j{0, 0, 1, 0}, k{0, 0, 0, 1};
    CHECK(max_diff(i * j, k) == 0);
    CHECK(max_diff(j * k, i) == 0);
    CHECK(max_diff(k * i, j) == 0);
    CHECK(max_diff(j * i, -k) == 0);
    CHECK(max_diff(i * i, quat{-1, 0, 0, 0}) == 0);
    CHECK(max_diff(i * j * k, quat{-1, 0, 0, 0}) == 0);  // ijk = -1 (Hamilton's rule)
}

TEST_CASE("product agrees with its expansion in components and its vector form") {
    keyrot::test::random_rotations rng(3);
    for (int n = 0; n < 100; ++n) {
        const quat p = rng.next(), q = rng.next();
        CAPTURE(n);
        const double a = p.w, b = p.x, c = p.y, d = p.z, e = q.w, f = q.x, g = q.y, h = q.z;
        const quat expanded{a * e - b * f - c * g - d * h, a * f + b * e + c * h - d * g,
                            a * g - b * h + c * e + d * f, a * h + b * g - c * f + d * e};
        CHECK(max_diff(p * q, expanded) <= 1e-15);
        // [a, v][e, w] = [ae - v.w, a w + e v + v x w]
        const vec3 v{b, c, d}, w{f, g, h};
        const vec3 vec = (a * w) + (e * v) + cross(v, w);
        CHECK(max_diff(p * q, quat{a * e - dot(v, w), vec.x, vec.y, vec.z}) <= 1e-15);
    }
}

namespace {

/// Dot2 (Ogita, Rump and Oishi) as a plain loop from sum = err = +0, every
/// term through TwoProduct and TwoSum: the form that defines the bits of
/// keyrot's products. The product's FMA clone, vectorised by the compiler,
/// must give the same bits. GCC 12 at -O3 broke them for a loop rearranged
/// to start from the first product, which is the same sum in IEEE
/// arithmetic: 15% of random products' components came out different.
template <std::size_t N>
double dot2_from_zero(const double (&x)[N], const double (&y)[N]) {
    double sum = 0, err = 0;
    for (std::size_t i = 0; i < N; ++i) {
        const double p = x[i] * y[i], p_err = std::fma(x[i], y[i], -p);
        const double t = sum + p, z = t - sum;
        err += (sum - (t - z)) + (p - z) + p_err;
        sum = t;
    }
    return sum + err;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b)); }

}  // namespace

TEST_CASE("dot2 and the product (its FMA clone where the CPU has one) give the plain loop's bits: signed zeros, underflow, cancellation") {
    // Products that underflow to -0 (with an error of -0), exact zeros of
    // either sign, subnormals, and terms that cancel.
    const double pool[] = {0.0, 1e-200, 1e-170, 5e-324, 3e-310, 1.0, 1e16, 0.1, 0.7071067811865476, 1e300};
    keyrot::test::random_rotations rng(11);
    const auto value = [&] {
        const double v = rng.uniform(0, 1) < 0.6 ? pool[static_cast<std::size_t>(rng.uniform(0, 10)) % 10]
                                                 : rng.uniform(-2, 2);
        return rng.uniform(0, 1) < 0.5 ? -v : v;
    };
    int zeros = 0, negative_zero_first = 0;
    for (int n = 0; n < 200000; ++n) {
        const double x[4] = {value(), value(), value(), value()}, y[4] = {value(), value(), value(), value()};
        const double x2[2] = {x[0], x[1]}, y2[2] = {y[0], y[1]}, x3[3] = {x[0], x[1], x[2]}, y3[3] = {y[0], y[1], y[2]};
        CAPTURE(n);
        REQUIRE(same_bits(dot2(x2, y2), dot2_from_zero(x2, y2)));
        REQUIRE(same_bits(dot2(x3, y3), dot2_from_zero(x3, y3)));
        REQUIRE(same_bits(dot2(x, y), dot2_from_zero(x, y)));
        zeros += dot2(x2, y2) == 0;
        negative_zero_first += x[0] * y[0] == 0 && std::signbit(x[0] * y[0]);
        // The product (built with FMA where the CPU has it) is four of them.
        const quat a{x[0], x[1], x[2], x[3]}, b{y[0], y[1], y[2], y[3]}, ab = a * b;
        REQUIRE(same_bits(ab.w, dot2_from_zero({a.w, -a.x, -a.y, -a.z}, {b.w, b.x, b.y, b.z})));
        REQUIRE(same_bits(ab.x, dot2_from_zero({a.w, a.x, a.y, -a.z}, {b.x, b.w, b.z, b.y})));
        REQUIRE(same_bits(ab.y, dot2_from_zero({a.w, -a.x, a.y, a.z}, {b.y, b.z, b.w, b.x})));
        REQUIRE(same_bits(ab.z, dot2_from_zero({a.w, a.x, -a.y, a.z}, {b.z, b.y, b.x, b.w})));
    }
    // Zero sums were met, and first products of -0 (where the loop's
    // first step gives +0), not just nonzero sums.
    CHECK(zeros > 1000);
    CHECK(negative_zero_first > 1000);
}

TEST_CASE("conjugate is the inverse of a unit quaternion") {
    keyrot::test::random_rotations rng(4);
    const quat q = rng.next();
    CHECK(max_diff(q * conjugate(q), quat{}) <= 1e-15);
}

TEST_CASE("rotate: 90 degrees about z takes x to y (active rotation)") {
    const double s = std::sqrt(0.5);
    const vec3 r = rotate(quat{s, 0, 0, s}, vec3{1, 0, 0});
    CHECK(near(r.x, 0, 1e-15));
    CHECK(near(r.y, 1, 1e-15));
    CHECK(near(r.z, 0, 1e-15));
}

TEST_CASE("exp and log are inverse, near identity, near pi and with w < 0") {
    const vec3 axis{0.48, -0.6, 0.64};  // unit
    for (double half : {1e-100, 1e-20, 1e-8, 0.3, 1.0, 1.5, 2.0, std::numbers::pi / 2, 3.0, std::numbers::pi - 1e-9}) {
        CAPTURE(half);
        const quat q = exp(half * axis);
        CHECK(near(q.w, std::cos(half), 1e-16));
        const vec3 l = log(q);
        CHECK(near(norm(l), half, 4e-16 * std::fmax(half, 1e-300) + 1e-300));
        CHECK(max_diff(exp(l), q) <= 4e-16);
    }
    CHECK(norm(log(quat{})) == 0);
    // -1: the full turn; the direction is undefined, keyrot picks +x
    const vec3 l = log(quat{-1, 0, 0, 0});
    CHECK(l.x == std::numbers::pi);
}

TEST_CASE("geodesic angle is sign-invariant and zero on itself") {
    keyrot::test::random_rotations rng(5);
    const quat a = rng.next(), b = rng.next();
    // Exactly 0, although conj(q) * q is not always exactly the identity
    // (for this q from a resampled track, its vector part is 2^-106 long).
    for (quat q : {a, b, quat{0.56360771033219, -0.38727639397466623, 0.25609099399209795, -0.6832135437183784}}) {
        CHECK(geodesic_angle(q, q) == 0);
        CHECK(geodesic_angle(q, -q) == 0);
    }
    CHECK(near(geodesic_angle(a, b), geodesic_angle(-a, b), 1e-15));
    CHECK(near(geodesic_angle(a, b), geodesic_angle(b, a), 1e-15));
    // 90 degrees about z from the identity
    const double s = std::sqrt(0.5);
    CHECK(near(geodesic_angle(quat{}, quat{s, 0, 0, s}), std::numbers::pi / 2, 1e-15));
}

TEST_CASE("norm of tiny and huge vectors neither underflows nor overflows") {
    CHECK(norm(vec3{3e-200, 4e-200, 0}) == doctest::Approx(5e-200).epsilon(1e-15));
    CHECK(norm(vec3{3e200, 4e200, 0}) == doctest::Approx(5e200).epsilon(1e-15));
}

TEST_CASE("rescaled: the largest component in [1, 2), the direction exact; zero stays zero") {
    const vec3 v = rescaled(vec3{1e-300, -3e-301, 0});
    CHECK(v.x == std::scalbn(1e-300, 997));  // 2^-997 <= 1e-300 < 2^-996
    CHECK(v.y == std::scalbn(-3e-301, 997));
    CHECK(v.z == 0);
    CHECK(rescaled(quat{4, 0, -2, 0}).w == 1);
    CHECK(rescaled(quat{4, 0, -2, 0}).y == -0.5);
    // A zero axis (an axis-angle key of angle 0 may have one) reaches it:
    // ilogb(0) is INT_MIN, whose negation the sanitizer build stops on.
    const vec3 zero = rescaled(vec3{0, 0, 0});
    CHECK((zero.x == 0 && zero.y == 0 && zero.z == 0));
    const quat q = rescaled(quat{0, 0, 0, 0});
    CHECK((q.w == 0 && q.x == 0 && q.y == 0 && q.z == 0));
}
