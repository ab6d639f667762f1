// SPDX-License-Identifier: MIT
#include "keyrot/interpolate.hpp"

#include <fmt/format.h>

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

vec3 slerp_segment::rotation_vector() const noexcept {
    const double angle = 2 * (half_ + half_lo_);
    return {static_cast<double>(angle * axis_x_), static_cast<double>(angle * axis_y_),
            static_cast<double>(angle * axis_z_)};
}

quat slerp(quat a, quat b, double h) noexcept { return slerp_segment(a, b).at(h); }

KEYROT_FMA_CLONES quat nlerp(quat a, quat b, double h) noexcept {
    // (a hold between equal keys is exactly the key, as slerp's is, not the lerp's rounding)
    if (h == 0 || (a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z)) return a;
    if (h == 1) return b;
    const double g = 1 - h;
    const quat l{std::fma(h, b.w, g * a.w), std::fma(h, b.x, g * a.x), std::fma(h, b.y, g * a.y),
                 std::fma(h, b.z, g * a.z)};
    const double n = norm(l);
    return n == 0 ? a : normalized(l, n);
}

quat squad_control(quat prev, quat cur, quat next) noexcept {
    const quat inv = conjugate(cur);
    const vec3 sum = log(inv * next) + log(inv * prev);
    return cur * exp(-0.25 * sum);
}

arc_curve::arc_curve(const arc_keys& k) noexcept : arc_(k.q0, k.q1) {
    if (k.squad) control_arc_.emplace(k.s0, k.s1);
}

quat arc_curve::at(double h) const noexcept {
    if (!control_arc_) return arc_.at(h);
    return slerp(arc_.at(h), control_arc_->at(h), 2 * h * (1 - h));
}

arc_keys segment::keys_for_arcs() const noexcept {
    if (how_ != method::squad) return {t0, t1, q0, q1, {}, {}, false};
    const auto& p = std::get<squad_points>(more_);
    return {t0, t1, q0, q1, p.s0, p.s1, true};
}

segment_curve segment::curve() const noexcept {
    segment_curve c(*this);
    if (how_ == method::slerp || how_ == method::squad) c.arcs_.emplace(keys_for_arcs());
    return c;
}

quat segment_curve::at(double h) const noexcept {
    switch (keys_.how_) {
        case method::slerp:
        case method::squad: return arcs_->at(h);
        case method::nlerp: return nlerp(keys_.q0, keys_.q1, h);
        case method::step: return keys_.q0;
        case method::cubic: return std::get<spline_segment>(keys_.more_).at(h);
        case method::cubicspline: {
            const auto c = [](quat q) { return std::array<double, 4>{q.w, q.x, q.y, q.z}; };
            const auto& [a, b] = std::get<segment::spline_keys>(keys_.more_);
            const auto v = hermite(c(a.rotation), c(a.rotation_out), c(b.rotation), c(b.rotation_in), keys_.t1 - keys_.t0, h);
            const quat q{v[0], v[1], v[2], v[3]};
            // The tangents could cancel the values (a curve through zero): its start stands in.
            return std::isfinite(norm(q)) && norm(q) > 0 ? normalized(q) : keys_.q0;
        }
        case method::euler: {
            const auto& k = std::get<segment::euler_angles>(keys_.more_);
            std::array<double, 3> e{};
            for (std::size_t j = 0; j < 3; ++j) e[j] = (1 - h) * k.e0[j] + h * k.e1[j];
            return from_euler(e, k.seq);
        }
    }
    return keys_.q0;
}

motion segment_curve::rates(double h) const noexcept {
    const segment& k = keys_;
    const double dt = k.t1 - k.t0;
    const auto c = [](quat q) { return std::array<double, 4>{q.w, q.x, q.y, q.z}; };
    const auto q = [](const std::array<double, 4>& v) { return quat{v[0], v[1], v[2], v[3]}; };
    switch (k.how_) {
        case method::slerp: return {(1 / dt) * arcs_->arc_.rotation_vector(), {}};
        case method::step: return {};
        case method::nlerp: {
            // the lerp l and its derivative (q1 - q0) / dt, then normalised
            const std::array<double, 4> a = c(k.q0), b = c(k.q1);
            std::array<double, 4> l{}, d{};
            for (std::size_t j = 0; j < 4; ++j) l[j] = (1 - h) * a[j] + h * b[j], d[j] = (b[j] - a[j]) / dt;
            if (norm(q(l)) == 0) return {};  // (b = -a at h = 1/2: nlerp holds a there)
            return motion_of(normalized_jet(quat_jet{q(l), q(d), {0, 0, 0, 0}}));
        }
        case method::cubicspline: {
            // hermite() and its derivatives in h, per second; then normalised
            const auto& [a, b] = std::get<segment::spline_keys>(k.more_);
            const double s = h, s2 = s * s, s3 = s2 * s;
            std::array<double, 4> v{}, d1{}, d2{};
            const auto av = c(a.rotation), ab = c(a.rotation_out), bv = c(b.rotation), ba = c(b.rotation_in);
            for (std::size_t j = 0; j < 4; ++j) {
                v[j] = (2 * s3 - 3 * s2 + 1) * av[j] + dt * (s3 - 2 * s2 + s) * ab[j] + (-2 * s3 + 3 * s2) * bv[j] +
                       dt * (s3 - s2) * ba[j];
                d1[j] = ((6 * s2 - 6 * s) * (av[j] - bv[j])) / dt + (3 * s2 - 4 * s + 1) * ab[j] + (3 * s2 - 2 * s) * ba[j];
                d2[j] = ((12 * s - 6) * (av[j] - bv[j])) / (dt * dt) + ((6 * s - 4) * ab[j] + (6 * s - 2) * ba[j]) / dt;
            }
            if (!(norm(q(v)) > 0) || !std::isfinite(norm(q(v)))) return {};  // (at() then holds the start)
            return motion_of(normalized_jet(quat_jet{q(v), q(d1), q(d2)}));
        }
        case method::euler: {
            // from_euler's product of three turns about axes, each angle linear in time
            const auto& [e0, e1, seq] = std::get<segment::euler_angles>(k.more_);
            quat_jet f[3];
            for (std::size_t j = 0; j < 3; ++j) {
                const double angle = (1 - h) * e0[j] + h * e1[j], rate = (e1[j] - e0[j]) / dt;
                vec3 axis;
                (seq.axes[j] == 0 ? axis.x : seq.axes[j] == 1 ? axis.y : axis.z) = 1;
                const quat e = from_axis_angle(axis, angle, angle_unit::radians);
                const vec3 half_rate = (rate / 2) * axis;
                f[j] = {e, e * quat{0, half_rate.x, half_rate.y, half_rate.z}, -(rate * rate / 4) * e};
            }
            return motion_of(seq.intrinsic ? f[0] * f[1] * f[2] : f[2] * f[1] * f[0]);
        }
        case method::squad: {
            // q = P exp(g phi_C / 2): P and S the inner slerps (constant body
            // rates wp, ws), C = P* S, g = 2h(1 - h). phi_C's derivatives from
            // C's motion, then the product's.
            const slerp_segment &arc = arcs_->arc_, &control_arc = *arcs_->control_arc_;
            const vec3 wp = (1 / dt) * arc.rotation_vector(), ws = (1 / dt) * control_arc.rotation_vector();
            const quat C = conjugate(arc.at(h)) * control_arc.at(h);
            const vec3 phi = 2.0 * log(C), wp_in_c = rotate(conjugate(C), wp);
            const vec3 wc = ws - wp_in_c, ac = cross(wc, wp_in_c);
            const mat3 jinv = inverse_rate_matrix(phi);
            const vec3 phi1 = jinv * wc, phi2 = jinv * (ac - rate_curvature(phi, phi1));
            const double g = 2 * h * (1 - h), g1 = 2 * (1 - 2 * h) / dt, g2 = -4 / (dt * dt);
            const vec3 e = g * phi, e1 = g1 * phi + g * phi1, e2 = g2 * phi + 2 * g1 * phi1 + g * phi2;
            const motion inner = motion_of(e, e1, e2);
            const vec3 u = rotate(conjugate(exp(0.5 * e)), wp);
            return {u + inner.velocity, cross(u, inner.velocity) + inner.acceleration};
        }
        case method::cubic: {
            const auto p = std::get<spline_segment>(k.more_).derivatives(h);
            return motion_of(p.phi, p.phi_dot, p.phi_ddot);
        }
    }
    return {};
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

void segment_builder::clear() noexcept {
    window_.clear(), splines_.clear();
    cubic_.times.clear(), cubic_.keys.clear(), cubic_.phi.clear(), cubic_.velocity.clear();
    cubic_.first = cubic_.final = cubic_.next = 0;
}

quat segment_builder::add(const key& k) {
    quat q = k.rotation;
    if (how_ == method::cubic) {
        auto& c = cubic_;
        if (!c.keys.empty() && dot(c.keys.back(), q) < 0) q = -q;
        // A key's first guess is its incoming segment's mean rate; the
        // first key's velocity is the first segment's, final at once.
        vec3 guess;
        if (!c.keys.empty()) {
            c.phi.push_back(rotation_vector_between(c.keys.back(), q));
            guess = (1 / (k.time - c.times.back())) * c.phi.back();
        }
        if (c.first + c.keys.size() == 1) c.velocity[0] = guess, c.final = 1;
        c.times.push_back(k.time), c.keys.push_back(q), c.velocity.push_back(guess);
        return q;
    }
    if (flips() && !window_.empty() && dot(window_.back().q, q) < 0) q = -q;
    std::array<double, 3> e{};
    if (how_ == method::euler)
        e = k.given_as == rep::euler && k.given ? k.given->euler_radians() : to_euler(k.rotation, *seq_).angles;
    window_.push_back({k.time, q, q, e});  // s = q until both neighbours are known
    // A key without a spline passes its rotation, with no tangents.
    if (how_ == method::cubicspline)
        splines_.push_back(k.spline ? static_cast<const spline_key&>(*k.spline)
                                    : spline_key{q, {0, 0, 0, 0}, {0, 0, 0, 0}, {}, {}, {}, {}});
    const std::size_t n = window_.size();
    if (how_ == method::squad && n >= 3) window_[n - 2].s = squad_control(window_[n - 3].q, window_[n - 2].q, q);
    return q;
}

bool segment_builder::pop(segment& out, bool end) {
    if (how_ == method::cubic) {
        auto& c = cubic_;
        // a segment whose keys' velocities are final
        while (c.next + 1 >= c.final)
            if (!solve_stretch(end)) return false;
        const std::size_t i = c.next++ - c.first;
        out.how_ = how_;
        out.t0 = c.times[i], out.t1 = c.times[i + 1], out.q0 = c.keys[i], out.q1 = c.keys[i + 1];
        out.more_ = spline_segment(out.q0, c.phi[i], out.t1 - out.t0, c.velocity[i], c.velocity[i + 1]);
        return true;
    }
    // squad's segment [0, 1] needs key 1's control point, which needs key 2
    const std::size_t needed = how_ == method::squad && !end ? 3 : 2;
    if (window_.size() < needed) return false;
    const entry& a = window_[0];
    const entry& b = window_[1];
    out.how_ = how_;
    out.t0 = a.time, out.t1 = b.time, out.q0 = a.q, out.q1 = b.q;
    switch (how_) {
        case method::squad: out.more_ = segment::squad_points{a.s, b.s}; break;
        case method::euler: out.more_ = segment::euler_angles{a.e, b.e, *seq_}; break;
        case method::cubicspline:
            out.more_ = segment::spline_keys{splines_[0], splines_[1]};
            splines_.erase(splines_.begin());
            break;
        default: out.more_ = std::monostate{};
    }
    window_.erase(window_.begin());
    return true;
}

bool segment_builder::solve_stretch(bool end) {
    auto& c = cubic_;
    const std::size_t received = c.first + c.keys.size();
    if (received < 2 || c.final == received) return false;
    if (!end && received < c.final + cubic_stretch + cubic_margin) return false;
    // From the last final key (exact, as the boundary of what follows) to
    // the stretch's look-ahead, or to the track's last key, whose velocity
    // (the last segment's mean rate) is final too.
    const std::size_t from = c.final - 1, to = end ? received - 1 : from + cubic_stretch + cubic_margin;
    if (to - from >= 2) {
        const std::size_t a = from - c.first, n = to - from + 1;
        const spline_status s = c.solver.solve(std::span(c.times).subspan(a, n), std::span(c.phi).subspan(a, n - 1),
                                               std::span(c.velocity).subspan(a, n));
        if (!s.converged)
            throw spline_error(fmt::format("the cubic spline's equations do not settle in {} rounds (steps near 180 "
                                           "degrees between keys of very uneven spacing): expected smaller steps, "
                                           "or another method",
                                           spline_max_rounds));
    }
    c.final = end ? received : to - cubic_margin + 1;
    // Forget the keys no segment or stretch needs again (now and then, so that it costs little).
    const std::size_t keep = std::min(c.next, c.final - 1);
    if (keep - c.first >= cubic_stretch) {
        const auto drop = static_cast<std::ptrdiff_t>(keep - c.first);
        c.times.erase(c.times.begin(), c.times.begin() + drop);
        c.keys.erase(c.keys.begin(), c.keys.begin() + drop);
        c.phi.erase(c.phi.begin(), c.phi.begin() + drop);
        c.velocity.erase(c.velocity.begin(), c.velocity.begin() + drop);
        c.first = keep;
    }
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
