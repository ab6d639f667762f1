// SPDX-License-Identifier: MIT
#include "keyrot/convert.hpp"

#include <cmath>
#include <numbers>

#include "core/fma_clones.hpp"
#include "keyrot/tolerances.hpp"

namespace keyrot {

namespace {

/// x * (hi + lo), rounded once: hi + lo is pi/180 or 180/pi to 106 bits,
/// so a unit conversion adds half an ulp, not one and a half.
KEYROT_FMA_CLONES double scale(double x, double hi, double lo) noexcept {
    const double p = x * hi;
    return p + (std::fma(x, hi, -p) + x * lo);
}

struct sin_cos {
    double sin, cos;
};

/// sin and cos of an angle in `unit`. Degrees are reduced by whole quarter
/// turns exactly (remquo, as GeographicLib's sincosd), so that 90, 180 and
/// 360 degrees give exact zeros and ones.
sin_cos sincos(double angle, angle_unit unit) noexcept {
    if (unit == angle_unit::radians) return {std::sin(angle), std::cos(angle)};
    int quarter = 0;
    const double rest = std::remquo(angle, 90.0, &quarter);
    const double r = to_radians(rest, angle_unit::degrees);
    // At 45 degrees sine and cosine are equal; make them so (sqrt(0.5) is correctly rounded).
    const double s = std::fabs(rest) == 45 ? std::copysign(std::sqrt(0.5), rest) : std::sin(r);
    const double c = std::fabs(rest) == 45 ? std::sqrt(0.5) : std::cos(r);
    switch (static_cast<unsigned>(quarter) & 3u) {
        case 0: return {s, c};
        case 1: return {c, -s};
        case 2: return {-s, -c};
        default: return {-c, s};
    }
}

}  // namespace

double to_radians(double angle, angle_unit from) noexcept {
    return from == angle_unit::degrees ? scale(angle, 0.017453292519943295, 2.9486522708701687e-19) : angle;
}

double from_radians(double radians, angle_unit to) noexcept {
    return to == angle_unit::degrees ? scale(radians, 57.29577951308232, -1.9878495670576283e-15) : radians;
}

std::optional<euler_seq> parse_euler_seq(std::string_view name) {
    if (name.size() != 3) return std::nullopt;
    euler_seq seq;
    seq.name = std::string(name);
    const bool upper = name[0] >= 'X' && name[0] <= 'Z';
    seq.intrinsic = upper;
    for (std::size_t i = 0; i < 3; ++i) {
        const char c = name[i];
        const char base = upper ? 'X' : 'x';
        if (c < base || c > base + 2) return std::nullopt;
        seq.axes[i] = c - base;
        if (i > 0 && seq.axes[i] == seq.axes[i - 1]) return std::nullopt;
    }
    return seq;
}

quat from_axis_angle(vec3 axis, double angle, angle_unit unit) noexcept {
    const sin_cos half = sincos(angle / 2, unit);
    if (const double n = norm(axis); !(n > 1e-150 && n < 1e150)) axis = rescaled(axis);
    const double s = half.sin / norm(axis);
    return {half.cos, s * axis.x, s * axis.y, s * axis.z};
}

quat from_rotvec(vec3 rotvec, angle_unit unit) noexcept {
    const double angle = norm(rotvec);
    if (angle == 0) return {};
    if (!(angle < 1e150)) {
        // So long that a double holds it only to many turns: no correction
        // below (its squares would overflow), and halved first, exactly, so
        // that the length of the half is finite even where the whole's is not.
        const vec3 h = 0.5 * rotvec;
        const double half_angle = norm(h);
        const sin_cos half = sincos(half_angle, unit);
        return {half.cos, half.sin * (h.x / half_angle), half.sin * (h.y / half_angle), half.sin * (h.z / half_angle)};
    }
    const sin_cos half = sincos(angle / 2, unit);
    // The length was rounded to a double: turn on by the rest, |v| - angle =
    // (|v|^2 - angle^2) / (|v| + angle), so that near 180 degrees (where an
    // ulp of the angle is 4e-16) the half angle is not off by that rounding;
    // and form the components in extended precision, rounding each once.
    // Only to a million: past it the rest can exceed 1e-10, and a first-order
    // turn by it is no longer a rotation (5.6e21 once gave a length of 700).
    long double d = 0;
    if (angle > 1e-150 && angle < 1e6) {
        const double rest = dot2({rotvec.x, rotvec.y, rotvec.z, angle}, {rotvec.x, rotvec.y, rotvec.z, -angle}) / (2 * angle);
        d = to_radians(rest, unit) / 2;
    }
    const long double s = (half.sin + half.cos * d) / angle;
    return {static_cast<double>(half.cos - half.sin * d), static_cast<double>(s * rotvec.x),
            static_cast<double>(s * rotvec.y), static_cast<double>(s * rotvec.z)};
}

namespace {

quat elementary(int axis, double angle, angle_unit unit) noexcept {
    const sin_cos half = sincos(angle / 2, unit);
    quat q{half.cos, 0, 0, 0};
    (axis == 0 ? q.x : axis == 1 ? q.y : q.z) = half.sin;
    return q;
}

double component(quat q, int axis) noexcept { return axis == 0 ? q.x : axis == 1 ? q.y : q.z; }

/// a b - c d with one rounding error (Kahan's algorithm with fma).
double difference_of_products(double a, double b, double c, double d) noexcept {
    const double cd = c * d;
    return std::fma(a, b, -cd) - std::fma(c, d, -cd);
}

double wrap_pi(double a) noexcept {
    if (a < -std::numbers::pi) return a + 2 * std::numbers::pi;
    if (a > std::numbers::pi) return a - 2 * std::numbers::pi;
    return a;
}

}  // namespace

quat from_euler(std::array<double, 3> angles, const euler_seq& seq, angle_unit unit) noexcept {
    const quat a = elementary(seq.axes[0], angles[0], unit);
    const quat b = elementary(seq.axes[1], angles[1], unit);
    const quat c = elementary(seq.axes[2], angles[2], unit);
    // Intrinsic: each rotation about the already-rotated axes, so the first
    // one is outermost. Extrinsic: the first one is applied first.
    return seq.intrinsic ? a * b * c : c * b * a;
}

quat from_matrix(const mat3& mat) noexcept {
    const auto& m = mat.m;
    const double trace = m[0][0] + m[1][1] + m[2][2];
    std::size_t best = 3;  // 0..2: a diagonal element, 3: the trace
    double largest = trace;
    for (std::size_t i = 0; i < 3; ++i)
        if (m[i][i] > largest) largest = m[i][i], best = i;
    std::array<double, 4> v{};  // x, y, z, w
    if (best == 3) {
        v = {m[2][1] - m[1][2], m[0][2] - m[2][0], m[1][0] - m[0][1], 1 + trace};
    } else {
        const std::size_t i = best, j = (i + 1) % 3, k = (j + 1) % 3;
        v[i] = 1 - trace + 2 * m[i][i];
        v[j] = m[j][i] + m[i][j];
        v[k] = m[k][i] + m[i][k];
        v[3] = m[k][j] - m[j][k];
    }
    return normalized({v[3], v[0], v[1], v[2]});
}

axis_angle to_axis_angle(quat q) noexcept {
    // q and -q are one rotation, and the sign of w comes at random: turned
    // to w >= 0 by a factor rather than a branch to mispredict.
    const double sign = std::copysign(1.0, q.w);
    q = {sign * q.w, sign * q.x, sign * q.y, sign * q.z};
    vec3 v = vector_part(q);
    const double sin_half = norm(v);
    if (sin_half == 0) return {};
    if (q.w == 0) {
        const double first = v.x != 0 ? v.x : v.y != 0 ? v.y : v.z;
        if (first < 0) v = -1.0 * v;
    }
    // Dividing (not multiplying by 1 / sin_half) keeps a single-axis rotation's axis exactly unit.
    return {{v.x / sin_half, v.y / sin_half, v.z / sin_half}, 2 * std::atan2(sin_half, q.w)};
}

vec3 to_rotvec(quat q) noexcept {
    const axis_angle aa = to_axis_angle(q);
    return aa.angle * aa.axis;
}

euler_angles to_euler(quat q, const euler_seq& seq) noexcept {
    // The paper's algorithm is for extrinsic sequences; an intrinsic sequence
    // is the reversed extrinsic one with the angles reversed.
    const bool extrinsic = !seq.intrinsic;
    int i = extrinsic ? seq.axes[0] : seq.axes[2];
    const int j = seq.axes[1];
    int k = extrinsic ? seq.axes[2] : seq.axes[0];
    const bool proper = i == k;
    if (proper) k = 3 - i - j;
    const int sign = (i - j) * (j - k) * (k - i) / 2;  // +1 for an even permutation

    double a, b, c, d;
    if (proper) {
        a = q.w;
        b = component(q, i);
        c = component(q, j);
        d = component(q, k) * sign;
    } else {
        a = q.w - component(q, j);
        b = component(q, i) + component(q, k) * sign;
        c = component(q, j) + q.w;
        d = component(q, k) * sign - component(q, i);
    }

    euler_angles out;
    auto& ang = out.angles;
    const int first = extrinsic ? 0 : 2;
    const int third = extrinsic ? 2 : 0;
    const double ab = std::hypot(a, b);
    const double cd = std::hypot(c, d);
    // Gimbal lock: the middle angle's distance from one of its two singular
    // values, computed directly so that tiny distances keep their precision.
    // Only where it may be that small: a ratio over 1e-15 puts it above
    // 2e-15, well beyond the threshold, and its atan2 is skipped.
    constexpr double far_ratio = 1e-15;
    static_assert(2 * far_ratio > 4 * tol::gimbal_lock);
    const auto locked = [](double y, double x) {
        return y <= x * far_ratio && 2 * std::atan2(y, x) <= tol::gimbal_lock;
    };
    const bool near_zero = locked(cd, ab), near_pi = locked(ab, cd);
    if (proper) {
        ang[1] = 2 * std::atan2(cd, ab);
    } else {
        // The paper's 2 atan2(cd, ab) - pi/2 cancels for a small middle angle.
        // With tan(x - pi/4) = (tan x - 1)/(tan x + 1) and cd^2 - ab^2 =
        // 4 (w y - x z') exactly, the small angle comes out to full precision.
        const double diff = 4 * difference_of_products(q.w, component(q, j), component(q, i), component(q, k) * sign);
        ang[1] = 2 * std::atan2(diff, (cd + ab) * (cd + ab));
    }
    const double half_sum = std::atan2(b, a);
    const double half_diff = std::atan2(d, c);
    if (near_zero) {
        out.gimbal_lock = true;
        ang[2] = 0;
        ang[0] = 2 * half_sum;
    } else if (near_pi) {
        out.gimbal_lock = true;
        ang[2] = 0;
        ang[0] = 2 * half_diff * (extrinsic ? -1 : 1);
    } else {
        ang[static_cast<std::size_t>(first)] = half_sum - half_diff;
        ang[static_cast<std::size_t>(third)] = half_sum + half_diff;
    }
    if (!proper) ang[static_cast<std::size_t>(third)] *= sign;
    for (double& x : ang) x = wrap_pi(x) + 0.0;  // + 0.0 turns -0 into 0
    return out;
}

euler_angles continuous_euler(quat q, const euler_seq& seq, const std::array<double, 3>& previous) noexcept {
    constexpr double pi = std::numbers::pi, turn = 2 * std::numbers::pi;
    const euler_angles canonical = to_euler(q, seq);
    const std::array<double, 3>& a = canonical.angles;
    const bool proper = seq.axes[0] == seq.axes[2];
    std::array<std::array<double, 3>, 2> candidates = {a, {a[0] + pi, proper ? -a[1] : pi - a[1], a[2] + pi}};
    double best_move = 0;
    std::size_t best = 0;
    for (std::size_t c = 0; c < 2; ++c) {
        double move = 0;
        for (std::size_t i = 0; i < 3; ++i) {
            double& x = candidates[c][i];
            x += turn * std::round((previous[i] - x) / turn);
            move += std::fabs(x - previous[i]);
        }
        if (c == 0 || move < best_move) best_move = move, best = c;
    }
    return {candidates[best], canonical.gimbal_lock};
}

KEYROT_FMA_CLONES mat3 to_matrix(quat q) noexcept {
    // The homogeneous form (entries over |q|^2) is exact for a quaternion
    // whose norm is a rounding error away from 1, and each entry is summed
    // in twice the precision: no 1 - 2(y^2 + z^2) cancellation near 180 degrees.
    const double w = q.w, x = q.x, y = q.y, z = q.z;
    const double s = 1 / inline_dot2({w, x, y, z}, {w, x, y, z});
    const double d = 2 * s;
    mat3 r;
    r.m[0] = {s * inline_dot2({w, x, -y, -z}, {w, x, y, z}), d * inline_dot2({x, -z}, {y, w}),
              d * inline_dot2({x, y}, {z, w})};
    r.m[1] = {d * inline_dot2({x, z}, {y, w}), s * inline_dot2({w, -x, y, -z}, {w, x, y, z}),
              d * inline_dot2({y, -x}, {z, w})};
    r.m[2] = {d * inline_dot2({x, -y}, {z, w}), d * inline_dot2({y, x}, {z, w}),
              s * inline_dot2({w, -x, -y, z}, {w, x, y, z})};
    return r;
}

}  // namespace keyrot
