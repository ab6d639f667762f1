// SPDX-License-Identifier: MIT
#include "keyrot/quat.hpp"

#include <cmath>
#include <initializer_list>

#include "core/fma_clones.hpp"

namespace keyrot {

vec3 operator+(vec3 a, vec3 b) noexcept { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
vec3 operator-(vec3 a, vec3 b) noexcept { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
vec3 operator*(double s, vec3 v) noexcept { return {s * v.x, s * v.y, s * v.z}; }
double dot(vec3 a, vec3 b) noexcept { return a.x * b.x + a.y * b.y + a.z * b.z; }
vec3 cross(vec3 a, vec3 b) noexcept {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double norm(vec3 v) noexcept {
    // hypot is slow; the plain sum of squares is as accurate whenever it can
    // neither underflow nor overflow.
    const double s = v.x * v.x + v.y * v.y + v.z * v.z;
    if (s > 1e-290 && s < 1e290) return std::sqrt(s);
    return std::hypot(v.x, v.y, v.z);
}

quat operator+(quat a, quat b) noexcept { return {a.w + b.w, a.x + b.x, a.y + b.y, a.z + b.z}; }

quat operator*(double s, quat q) noexcept { return {s * q.w, s * q.x, s * q.y, s * q.z}; }

quat operator-(quat q) noexcept { return {-q.w, -q.x, -q.y, -q.z}; }

template <std::size_t N>
double dot2(const double (&x)[N], const double (&y)[N]) noexcept {
    return inline_dot2(x, y);
}
template double dot2<2>(const double (&)[2], const double (&)[2]) noexcept;
template double dot2<3>(const double (&)[3], const double (&)[3]) noexcept;
template double dot2<4>(const double (&)[4], const double (&)[4]) noexcept;

KEYROT_FMA_CLONES quat operator*(quat a, quat b) noexcept {
    return {inline_dot2({a.w, -a.x, -a.y, -a.z}, {b.w, b.x, b.y, b.z}),
            inline_dot2({a.w, a.x, a.y, -a.z}, {b.x, b.w, b.z, b.y}),
            inline_dot2({a.w, -a.x, a.y, a.z}, {b.y, b.z, b.w, b.x}),
            inline_dot2({a.w, a.x, -a.y, a.z}, {b.z, b.y, b.x, b.w})};
}

double dot(quat a, quat b) noexcept { return a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z; }

double norm(quat q) noexcept {
    const double s = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;  // see norm(vec3)
    if (s > 1e-290 && s < 1e290) return std::sqrt(s);
    return std::hypot(std::hypot(q.w, q.x), std::hypot(q.y, q.z));
}

quat conjugate(quat q) noexcept { return {q.w, -q.x, -q.y, -q.z}; }

vec3 vector_part(quat q) noexcept { return {q.x, q.y, q.z}; }

quat normalized(quat q) noexcept { return normalized(q, norm(q)); }

quat normalized(quat q, double n) noexcept {
    if (!(n > 1e-150 && n < 1e150)) {  // past the largest double, or among the subnormals
        q = rescaled(q);
        n = norm(q);
    }
    return {q.w / n, q.x / n, q.y / n, q.z / n};
}

namespace {

/// e with the largest of these magnitudes in [2^e, 2^(e+1)); 0 where all
/// are zero or NaN, whose ilogb (INT_MIN here) could not be negated.
int exponent_of_largest(std::initializer_list<double> xs) noexcept {
    double largest = 0;
    for (double x : xs) largest = std::fmax(largest, std::fabs(x));
    return largest == 0 || std::isnan(largest) ? 0 : std::ilogb(largest);
}

}  // namespace

// scalbn rather than a product with 2^-e, which does not exist for e = -1074.
vec3 rescaled(vec3 v) noexcept {
    const int e = exponent_of_largest({v.x, v.y, v.z});
    return {std::scalbn(v.x, -e), std::scalbn(v.y, -e), std::scalbn(v.z, -e)};
}

quat rescaled(quat q) noexcept {
    const int e = exponent_of_largest({q.w, q.x, q.y, q.z});
    return {std::scalbn(q.w, -e), std::scalbn(q.x, -e), std::scalbn(q.y, -e), std::scalbn(q.z, -e)};
}

quat exp(vec3 v) noexcept {
    const double angle = norm(v);
    if (angle == 0) return {};
    const double s = std::sin(angle) / angle;
    return {std::cos(angle), s * v.x, s * v.y, s * v.z};
}

vec3 log(quat q) noexcept {
    const vec3 v = vector_part(q);
    const double sin_half = norm(v);
    // atan2 keeps full relative accuracy for tiny and for near-pi angles,
    // where acos(w) would lose half the digits.
    const double half = std::atan2(sin_half, q.w);
    if (sin_half == 0) return q.w >= 0 ? vec3{} : vec3{half, 0, 0};
    return (half / sin_half) * v;
}

half_angle geodesic_half_angle(quat a, quat b) noexcept {
    // conj(a) * b is within about 2^-106 of exact, but for b = a not always
    // exactly (1, 0, 0, 0): a rotation compared with itself (a file with a
    // copy of itself) must differ by 0, not 1e-30 degrees.
    const auto same = [](quat p, quat q) { return p.w == q.w && p.x == q.x && p.y == q.y && p.z == q.z; };
    if (same(a, b) || same(a, -b)) return {0, 1};
    const quat r = conjugate(a) * b;
    return {norm(vector_part(r)), std::fabs(r.w)};
}

double geodesic_angle(half_angle h) noexcept { return 2 * std::atan2(h.sin, h.cos); }

double geodesic_angle(quat a, quat b) noexcept { return geodesic_angle(geodesic_half_angle(a, b)); }

vec3 rotate(quat q, vec3 v) noexcept {
    return vector_part(q * quat{0, v.x, v.y, v.z} * conjugate(q));
}

}  // namespace keyrot
