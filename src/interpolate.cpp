#include "keyrot/interpolate.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

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

quat slerp(quat a, quat b, double h) noexcept {
    if (h == 0) return a;
    if (h == 1) return b;
    // Szeliski's form (seed 004): b = a r, turn a by the fraction h of r.
    // atan2 keeps the angle accurate when a and b are close or opposite.
    const quat r = conjugate(a) * b;
    const vec3 v = vector_part(r);
    const double sin_half = norm(v);
    const double half = std::atan2(sin_half, r.w);  // [0, pi]
    if (sin_half == 0) {
        if (r.w >= 0) return a;
        const double turn = h * std::numbers::pi;  // b = -a: a full turn
        return a * quat{std::cos(turn), std::sin(turn), 0, 0};
    }
    const double k = std::sin(h * half) / sin_half;
    return a * quat{std::cos(h * half), k * v.x, k * v.y, k * v.z};
}

quat nlerp(quat a, quat b, double h) noexcept {
    if (h == 0) return a;
    if (h == 1) return b;
    const double g = 1 - h;
    const quat l{g * a.w + h * b.w, g * a.x + h * b.x, g * a.y + h * b.y, g * a.z + h * b.z};
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
    if (m == method::squad) {
        s_ = q_;
        for (std::size_t i = 1; i + 1 < n; ++i) s_[i] = squad_control(q_[i - 1], q_[i], q_[i + 1]);
    }
    if (m == method::euler) {
        if (!seq_) throw usage_error("--method euler needs an Euler sequence: expected --euler SEQ");
        euler_.reserve(n);
        for (const key& k : t.keys) euler_.push_back(k.euler ? *k.euler : to_euler(k.rotation, *seq_).angles);
    }
}

quat rotation_curve::at(std::size_t i, double h) const noexcept {
    switch (method_) {
        case method::slerp: return slerp(q_[i], q_[i + 1], h);
        case method::nlerp: return nlerp(q_[i], q_[i + 1], h);
        case method::squad: return squad(q_[i], q_[i + 1], s_[i], s_[i + 1], h);
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
