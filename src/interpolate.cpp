#include "keyrot/interpolate.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "keyrot/tolerances.hpp"

namespace keyrot {

std::optional<method> parse_method(std::string_view name) {
    for (std::size_t i = 0; i < method_names.size(); ++i)
        if (method_names[i] == name) return static_cast<method>(i);
    return std::nullopt;
}

std::string_view to_string(method m) noexcept { return method_names[static_cast<std::size_t>(m)]; }

std::optional<path> parse_path(std::string_view name) {
    for (std::size_t i = 0; i < path_names.size(); ++i)
        if (path_names[i] == name) return static_cast<path>(i);
    return std::nullopt;
}

std::string_view to_string(path p) noexcept { return path_names[static_cast<std::size_t>(p)]; }

slerp_segment::slerp_segment(quat a, quat b) noexcept : a_(a), b_(b) {
    // Szeliski's form (seed 004): b = a r; turn a by the fraction h of r.
    // The product is compensated, so r is accurate for keys that are close
    // or opposite, and atan2 keeps the angle accurate at both ends.
    const quat r = conjugate(a) * b;
    const vec3 v = vector_part(r);
    const double sin_half = norm(v);
    if (r.w < 0 && sin_half <= tol::opposite_keys) {
        half_ = std::numbers::pi;  // b = -a: a full turn about x
        return;
    }
    if (sin_half == 0) return;  // b = a
    // The axis and the half angle in [0, pi] to about 64 bits (the half
    // angle split into hi + lo): an ulp of a double near pi is 4e-16, which
    // would double into the rotation.
    const long double x = v.x, y = v.y, z = v.z;
    const long double len = std::sqrt(x * x + y * y + z * z);
    axis_x_ = x / len, axis_y_ = y / len, axis_z_ = z / len;
    const long double half = std::atan2(len, static_cast<long double>(r.w));
    half_ = static_cast<double>(half);
    half_lo_ = static_cast<double>(half - half_);
}

quat slerp_segment::at(double h) const noexcept {
    if (h == 0) return a_;
    if (h == 1) return b_;
    // h (hi + lo) = phi + phi_lo; sin and cos of phi corrected to first
    // order, and the turn p = (cos, sin axis) rounded once.
    const double phi = h * half_;
    const long double phi_lo = std::fma(h, half_, -phi) + static_cast<long double>(h) * half_lo_;
    const long double s = std::sin(phi), c = std::cos(phi);
    const long double sin_phi = s + c * phi_lo;
    const quat p{static_cast<double>(c - s * phi_lo), static_cast<double>(sin_phi * axis_x_),
                 static_cast<double>(sin_phi * axis_y_), static_cast<double>(sin_phi * axis_z_)};
    return a_ * p;
}

quat slerp(quat a, quat b, double h) noexcept { return slerp_segment(a, b).at(h); }

quat nlerp(quat a, quat b, double h) noexcept {
    if (h == 0) return a;
    if (h == 1) return b;
    const double g = 1 - h;
    const quat l{std::fma(h, b.w, g * a.w), std::fma(h, b.x, g * a.x), std::fma(h, b.y, g * a.y),
                 std::fma(h, b.z, g * a.z)};
    return norm(l) == 0 ? a : normalized(l);
}

quat squad_control(quat prev, quat cur, quat next) noexcept {
    const quat inv = conjugate(cur);
    const vec3 sum = log(inv * next) + log(inv * prev);
    return cur * exp(-0.25 * sum);
}

quat squad(quat q0, quat q1, quat s0, quat s1, double h) noexcept {
    return slerp(slerp(q0, q1, h), slerp(s0, s1, h), 2 * h * (1 - h));
}

rotation_curve::rotation_curve(const track& t, method m, path p) : method_(m), seq_(t.euler) {
    const std::size_t n = t.keys.size();
    q_.reserve(n);
    for (const key& k : t.keys) {
        quat q = k.rotation;
        if (p == path::shortest && !q_.empty() && dot(q_.back(), q) < 0) q = -q;
        q_.push_back(q);
    }
    if (m == method::slerp || m == method::squad)
        for (std::size_t i = 0; i + 1 < n; ++i) slerps_.emplace_back(q_[i], q_[i + 1]);
    if (m == method::squad) {
        s_ = q_;
        for (std::size_t i = 1; i + 1 < n; ++i) s_[i] = squad_control(q_[i - 1], q_[i], q_[i + 1]);
        for (std::size_t i = 0; i + 1 < n; ++i) slerps_.emplace_back(s_[i], s_[i + 1]);
    }
    if (m == method::euler) {
        if (!seq_) throw usage_error("--method euler needs an Euler sequence: expected --euler SEQ");
        euler_.reserve(n);
        for (const key& k : t.keys) euler_.push_back(k.euler ? *k.euler : to_euler(k.rotation, *seq_).angles);
    }
}

quat rotation_curve::at(std::size_t i, double h) const noexcept {
    switch (method_) {
        case method::slerp: return slerps_[i].at(h);
        case method::nlerp: return nlerp(q_[i], q_[i + 1], h);
        case method::squad: {
            const std::size_t segments = q_.size() - 1;
            return slerp(slerps_[i].at(h), slerps_[segments + i].at(h), 2 * h * (1 - h));
        }
        case method::step: return q_[i];
        case method::euler: {
            std::array<double, 3> e{};
            for (std::size_t j = 0; j < 3; ++j) e[j] = (1 - h) * euler_[i][j] + h * euler_[i + 1][j];
            return from_euler(e, *seq_);
        }
    }
    return q_[i];
}

translation_curve::translation_curve(const track& t, method m) : hold_(m == method::step) {
    for (const key& k : t.keys)
        if (k.translation) {
            times_.push_back(k.time);
            values_.push_back(*k.translation);
        }
}

std::optional<vec3> translation_curve::at(double time, double tol) const noexcept {
    if (times_.empty()) return std::nullopt;
    // The first key after `time`; the segment is [j - 1, j].
    const auto j = static_cast<std::size_t>(std::upper_bound(times_.begin(), times_.end(), time) - times_.begin());
    if (j < times_.size() && times_[j] - time <= tol) return values_[j];
    if (j == 0) return values_.front();
    if (j == times_.size() || hold_ || time - times_[j - 1] <= tol) return values_[j - 1];
    const double h = (time - times_[j - 1]) / (times_[j] - times_[j - 1]);
    return (1 - h) * values_[j - 1] + h * values_[j];
}

}  // namespace keyrot
