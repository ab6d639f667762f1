#include "keyrot/interpolate.hpp"

#include <cmath>
#include <numbers>

#include "core/fma_clones.hpp"
#include "keyrot/tolerances.hpp"

namespace keyrot {

slerp_segment::slerp_segment(quat a, quat b) noexcept : a_(a), b_(b) {
    // Szeliski's form (Computer Vision, Algorithm 2.1): b = a r; turn a by the fraction h of r.
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

KEYROT_FMA_CLONES quat slerp_segment::at(double h) const noexcept {
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

KEYROT_FMA_CLONES quat nlerp(quat a, quat b, double h) noexcept {
    // (a hold between equal keys is exactly the key, as slerp's is, not the lerp's rounding)
    if (h == 0 || (a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z)) return a;
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

segment_curve segment::curve() const noexcept {
    segment_curve c(*this);
    if (how_ == method::slerp || how_ == method::squad) c.arc_ = slerp_segment(q0, q1);
    if (how_ == method::squad) c.control_arc_ = slerp_segment(s0_, s1_);
    return c;
}

quat segment_curve::at(double h) const noexcept {
    switch (keys_.how_) {
        case method::slerp: return arc_.at(h);
        case method::nlerp: return nlerp(keys_.q0, keys_.q1, h);
        // Shoemake's squad: slerp(slerp(q0, q1, h), slerp(s0, s1, h), 2h(1 - h)).
        case method::squad: return slerp(arc_.at(h), control_arc_.at(h), 2 * h * (1 - h));
        case method::step: return keys_.q0;
        case method::cubicspline: {
            const auto c = [](quat q) { return std::array<double, 4>{q.w, q.x, q.y, q.z}; };
            const spline_key &a = keys_.spline0_, &b = keys_.spline1_;
            const auto v = hermite(c(a.rotation), c(a.rotation_out), c(b.rotation), c(b.rotation_in), keys_.t1 - keys_.t0, h);
            const quat q{v[0], v[1], v[2], v[3]};
            // The tangents could cancel the values (a curve through zero): its start stands in.
            return std::isfinite(norm(q)) && norm(q) > 0 ? normalized(q) : keys_.q0;
        }
        case method::euler: {
            std::array<double, 3> e{};
            for (std::size_t j = 0; j < 3; ++j) e[j] = (1 - h) * keys_.e0_[j] + h * keys_.e1_[j];
            return from_euler(e, keys_.seq_);
        }
    }
    return keys_.q0;
}

std::array<double, 4> hermite(const std::array<double, 4>& v0, const std::array<double, 4>& b0,
                              const std::array<double, 4>& v1, const std::array<double, 4>& a1, double seconds,
                              double s) noexcept {
    std::array<double, 4> p{};
    hermite(v0, b0, v1, a1, seconds, s, p);
    return p;
}

void hermite(std::span<const double> v0, std::span<const double> b0, std::span<const double> v1,
             std::span<const double> a1, double seconds, double s, std::span<double> out) noexcept {
    const double s2 = s * s, s3 = s2 * s;
    const double c0 = 2 * s3 - 3 * s2 + 1, cb = seconds * (s3 - 2 * s2 + s), c1 = -2 * s3 + 3 * s2,
                 ca = seconds * (s3 - s2);
    for (std::size_t j = 0; j < out.size(); ++j) out[j] = c0 * v0[j] + cb * b0[j] + c1 * v1[j] + ca * a1[j];
}

void check_method(method m, const std::optional<euler_seq>& seq) {
    if (m == method::euler && !seq) throw option_error(option::euler_sequence, "method euler needs an Euler sequence");
}

segment_builder::segment_builder(method m, path p, const std::optional<euler_seq>& seq)
    : how_(m), way_(p), seq_(seq) {
    check_method(m, seq);
}

quat segment_builder::add(const key& k) {
    quat q = k.rotation;
    const bool flips = way_ == path::shortest && how_ != method::cubicspline;
    if (flips && !window_.empty() && dot(window_.back().q, q) < 0) q = -q;
    std::array<double, 3> e{};
    if (how_ == method::euler) e = k.euler ? *k.euler : to_euler(k.rotation, *seq_).angles;
    window_.push_back({k.time, q, q, e, {}});  // s = q until both neighbours are known
    // A key without a spline passes its rotation, with no tangents.
    if (how_ == method::cubicspline)
        window_.back().spline =
            k.spline ? static_cast<const spline_key&>(*k.spline) : spline_key{q, {0, 0, 0, 0}, {0, 0, 0, 0}, {}, {}, {}, {}};
    const std::size_t n = window_.size();
    if (how_ == method::squad && n >= 3) window_[n - 2].s = squad_control(window_[n - 3].q, window_[n - 2].q, q);
    return q;
}

bool segment_builder::pop(segment& out, bool end) {
    // squad's segment [0, 1] needs key 1's control point, which needs key 2
    const std::size_t needed = how_ == method::squad && !end ? 3 : 2;
    if (window_.size() < needed) return false;
    const entry& a = window_[0];
    const entry& b = window_[1];
    out.how_ = how_;
    out.t0 = a.time, out.t1 = b.time, out.q0 = a.q, out.q1 = b.q;
    out.s0_ = a.s, out.s1_ = b.s;
    if (how_ == method::euler) out.e0_ = a.e, out.e1_ = b.e, out.seq_ = *seq_;
    if (how_ == method::cubicspline) out.spline0_ = a.spline, out.spline1_ = b.spline;
    window_.erase(window_.begin());
    return true;
}

rotation_curve::rotation_curve(const track& t, method m, path p) {
    segment_builder builder(m, p, t.euler);
    segment s;
    for (const key& k : t.keys) {
        keys_.push_back(builder.add(k));
        while (builder.pop(s, false)) segments_.push_back(s.curve());
    }
    while (builder.pop(s, true)) segments_.push_back(s.curve());
}

}  // namespace keyrot
