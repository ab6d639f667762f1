// SPDX-License-Identifier: MIT
#include "keyrot/rotation_spline.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "keyrot/motion.hpp"

namespace keyrot {

vec3 rotation_vector_between(quat a, quat b) noexcept {
    quat r = conjugate(a) * b;
    if (r.w < 0) r = -r;
    return 2.0 * log(r);
}

namespace {

/// The block tridiagonal system of the inner keys' velocities, factored
/// once (block Thomas: lower blocks, inverted pivots, eliminated uppers),
/// solved for each right-hand side.
class block_tridiagonal {
public:
    /// Row k: lower[k] x[k-1] + diagonal[k] x[k] + upper[k] x[k+1] = b[k].
    void add_row(const mat3& lower, const mat3& diagonal, const mat3& upper) {
        const std::size_t k = pivot_.size();
        mat3 d = diagonal;
        if (k > 0) d = d + (-1.0) * (lower * eliminated_[k - 1]);
        pivot_.push_back(inverse(d));
        eliminated_.push_back(pivot_.back() * upper);
        lower_.push_back(lower);
    }
    /// Forgets the rows (their memory kept).
    void clear() noexcept { lower_.clear(), pivot_.clear(), eliminated_.clear(); }
    /// x for right-hand side b (both as many as rows).
    void solve(const std::vector<vec3>& b, std::vector<vec3>& x) const {
        const std::size_t m = pivot_.size();
        x.resize(m);
        for (std::size_t k = 0; k < m; ++k) x[k] = pivot_[k] * (k > 0 ? b[k] - lower_[k] * x[k - 1] : b[k]);
        for (std::size_t k = m - 1; k-- > 0;) x[k] = x[k] - eliminated_[k] * x[k + 1];
    }

private:
    std::vector<mat3> lower_, pivot_, eliminated_;
};

/// What each round needs of an inner key's segments, worked out once a stretch.
struct inner {
    mat3 lower, upper;            // 2/dt_k J(phi_k), 2/dt_{k+1} Jinv(phi_{k+1})
    mat3 jinv;                    // Jinv(phi_k)
    curvature_coefficients bend;  // of phi_k
    double diagonal;              // 4 (1/dt_k + 1/dt_{k+1})
    vec3 fixed;                   // the right-hand side but the curvature
};

}  // namespace

struct spline_solver::workspace {
    std::vector<double> dt;
    std::vector<inner> each;
    block_tridiagonal system;
    std::vector<vec3> minus_residual, step;
};

spline_solver::spline_solver() = default;
spline_solver::~spline_solver() = default;
spline_solver::spline_solver(const spline_solver&) {}
spline_solver& spline_solver::operator=(const spline_solver&) { return *this; }

spline_status spline_solver::solve(std::span<const double> times, std::span<const vec3> phi, std::span<vec3> w) {
    if (!work_) work_ = std::make_unique<workspace>();
    workspace& ws = *work_;
    const std::size_t n = times.size();
    auto& dt = ws.dt;
    dt.resize(n - 1);
    for (std::size_t i = 0; i + 1 < n; ++i) dt[i] = times[i + 1] - times[i];
    // Unknown k is key k + 1's velocity. The angular acceleration at the
    // end of segment k, J(phi_k) phi_k'' + curvature(phi_k, phi_k'), equals
    // phi_{k+1}''(0) at the start of the next; with phi cubic that is
    //   2/dt_k J(phi_k) w_k + 4 (1/dt_k + 1/dt_{k+1}) w_{k+1} + 2/dt_{k+1} Jinv(phi_{k+1}) w_{k+2}
    //     = 6 (phi_k / dt_k^2 + phi_{k+1} / dt_{k+1}^2) - curvature(phi_k, Jinv(phi_k) w_{k+1}).
    const std::size_t m = n - 2;
    auto& each = ws.each;
    each.clear();
    mat3 jinv_next = inverse_rate_matrix(phi[0]);
    for (std::size_t k = 0; k < m; ++k) {
        inner& e = each.emplace_back();
        const double a = dt[k], b = dt[k + 1];
        e.jinv = jinv_next;
        e.bend = curvature_of(phi[k]);
        jinv_next = inverse_rate_matrix(phi[k + 1]);
        e.lower = (2 / a) * rate_matrix(phi[k]);
        e.upper = (2 / b) * jinv_next;
        e.diagonal = 4 * (1 / a + 1 / b);
        e.fixed = 6 * ((1 / (a * a)) * phi[k] + (1 / (b * b)) * phi[k + 1]);
        if (k == 0) e.fixed = e.fixed - e.lower * w[0];
        if (k + 1 == m) e.fixed = e.fixed - e.upper * w[n - 1];
    }
    // Each round solves J step = -residual. With J the linear part alone
    // (factored once) that is scipy's iteration, cheap and enough where the
    // steps are small. Where a round does not shrink the step tenfold
    // (large steps), J takes the curvature's derivative at the current
    // velocities too (Newton's method), kept while it shrinks the step
    // tenfold a round and factored again where it does not: a few rounds
    // where scipy's takes dozens.
    const mat3 none{};
    block_tridiagonal& system = ws.system;
    const auto factor = [&](bool newton) {
        system.clear();
        for (std::size_t k = 0; k < m; ++k) {
            const inner& e = each[k];
            mat3 d{{{{e.diagonal, 0, 0}, {0, e.diagonal, 0}, {0, 0, e.diagonal}}}};
            if (newton) d = d + curvature_jacobian(phi[k], e.jinv * w[k + 1], e.bend) * e.jinv;
            system.add_row(k > 0 ? e.lower : none, d, k + 1 < m ? e.upper : none);
        }
    };
    factor(false);
    bool refactor = false;
    double last_step = std::numeric_limits<double>::infinity();
    auto& minus_residual = ws.minus_residual;
    auto& step = ws.step;
    minus_residual.resize(m);
    spline_status out;
    out.converged = false;
    while (out.rounds < spline_max_rounds && !out.converged) {
        ++out.rounds;
        if (refactor) factor(true);
        for (std::size_t k = 0; k < m; ++k) {
            const inner& e = each[k];
            const vec3 x = w[k + 1];
            vec3 r = e.diagonal * x + rate_curvature(phi[k], e.jinv * x, e.bend) - e.fixed;
            if (k > 0) r = r + e.lower * w[k];
            if (k + 1 < m) r = r + e.upper * w[k + 2];
            minus_residual[k] = (-1.0) * r;
        }
        system.solve(minus_residual, step);
        out.converged = true;
        double largest = 0;
        for (std::size_t k = 0; k < m; ++k) {
            const vec3 b = w[k + 1], a = b + step[k];
            for (const auto& [x, y] : {std::pair{a.x, b.x}, std::pair{a.y, b.y}, std::pair{a.z, b.z}})
                if (!(std::fabs(x - y) <= 1e-13 * (1 + std::fabs(x)))) out.converged = false;
            largest = std::fmax(largest, norm(step[k]));
            w[k + 1] = a;
        }
        refactor = largest > 0.1 * last_step;
        last_step = largest;
    }
    return out;
}

spline_rates spline_key_rates(std::span<const double> times, std::span<const quat> keys) {
    const std::size_t n = keys.size();
    spline_rates out;
    std::vector<vec3>& w = out.velocity;
    // The first and last keys move at their segments' mean rates; the inner
    // ones start from their incoming segment's.
    std::vector<vec3> phi(n - 1);
    w.resize(n);
    for (std::size_t i = 1; i < n; ++i) {
        phi[i - 1] = rotation_vector_between(keys[i - 1], keys[i]);
        w[i] = (1 / (times[i] - times[i - 1])) * phi[i - 1];
    }
    w[0] = w[1];
    if (n > 2) out.status = spline_solver().solve(times, phi, w);
    return out;
}

spline_segment::spline_segment(quat q0, vec3 phi, double dt, vec3 w0, vec3 w1) noexcept : q0_(q0), dt_(dt) {
    // phi(0) = 0, phi'(0) = w0 (J(0) is the identity), phi(dt) = the
    // segment's rotation vector, phi'(dt) = Jinv(phi) w1.
    const vec3 end_rate = inverse_rate_matrix(phi) * w1;
    c1_ = w0;
    c2_ = (1 / (dt * dt)) * (3 * phi - (2 * dt) * w0 - dt * end_rate);
    c3_ = (1 / (dt * dt * dt)) * (dt * w0 + dt * end_rate - 2 * phi);
}

quat spline_segment::at(double h) const noexcept {
    if (h == 0) return q0_;
    const double s = h * dt_;
    const vec3 phi = s * (s * (s * c3_ + c2_) + c1_);
    return q0_ * exp(0.5 * phi);
}

spline_segment::point spline_segment::derivatives(double h) const noexcept {
    const double s = h * dt_;
    return {s * (s * (s * c3_ + c2_) + c1_), s * (3 * s * c3_ + 2 * c2_) + c1_, 6 * s * c3_ + 2 * c2_};
}

}  // namespace keyrot
