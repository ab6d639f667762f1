// SPDX-License-Identifier: MIT
#include "app/plots.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ostream>

#include "app/usage_error.hpp"

namespace keyrot::detail {

namespace {

/// Samples of a curve across the plot's width: a segment gets its share of
/// them by its duration, and at least one (its first key).
constexpr double samples_across = 1600;

std::string_view unit_name(angle_unit unit) { return unit == angle_unit::degrees ? "deg" : "rad"; }

constexpr std::array<svg::colour, 4> curve_hues = {svg::colour::blue, svg::colour::vermillion, svg::colour::green,
                                                   svg::colour::purple};

/// A panel of the rotation curves `values` gives names to, with no points yet.
svg::panel rotation_panel(const std::string& title, const rotation_values& values) {
    svg::panel p{title, "time (s)", values.y_label(), {}, {}, {}, false, false};
    const std::vector<std::string> labels = values.labels();
    for (std::size_t i = 0; i < labels.size(); ++i) p.curves.push_back({labels[i], curve_hues[i], {}});
    return p;
}

/// The tolerance as a panel's dashed line.
svg::level tolerance_level(double deg) { return {fmt::format("tolerance {} deg", deg), deg}; }

/// The most keys a panel marks: more would hide the curves (which then
/// pass through keys a few pixels apart anyway).
constexpr std::size_t most_marked = 200;

/// Says under the axis that `count` keys are not marked.
void say_unmarked(svg::panel& p, std::size_t count, const std::string& label) {
    p.x_label += fmt::format("; {} {}, too close to mark", count, label);
}

/// Marks `at`, a point of curve `i` of panel `p`, in the curve's colour:
/// a set of marks a curve, the first named `label`.
void mark(svg::panel& p, std::size_t i, svg::point at, const std::string& label) {
    while (p.marked.size() <= i) {
        const svg::curve& c = p.curves[p.marked.size()];
        p.marked.push_back({p.marked.empty() ? label : "", c.hue, svg::mark_shape::dot, {}});
    }
    p.marked[i].points.push_back(at);
}

}  // namespace

namespace {

/// How a drawing's Euler curves are written: continuous, in its sequence and unit.
write_options euler_curves(const rotation_drawing& d) {
    write_options w;
    w.representation = rep::euler;
    w.euler = d.euler;
    w.angles = d.unit;
    w.euler_continuous = true;
    return w;
}

}  // namespace

rotation_values::rotation_values(const rotation_drawing& d, quat first, const std::optional<euler_seq>& euler,
                                 method how)
    : d_(d), first_(first), euler_(euler_curves(d), format::csv) {
    euler_.begin_track(euler, how, std::nullopt);
}

std::array<double, 4> rotation_values::next(double time, quat q) {
    std::array<double, 4> v{};
    switch (d_.curves) {
        case plot_curves::quat:
            if (started_ && dot(q, previous_) < 0) q = -q;
            previous_ = q;
            v = {q.w, q.x, q.y, q.z};
            break;
        case plot_curves::euler: {
            const auto& angles = euler_.of(time, q)->values;
            std::copy_n(angles.begin(), 3, v.begin());
            break;
        }
        case plot_curves::angle: v[0] = from_radians(geodesic_angle(first_, q), d_.unit); break;
    }
    started_ = true;
    return v;
}

std::vector<std::string> rotation_values::labels() const {
    switch (d_.curves) {
        case plot_curves::quat: return {"w", "x", "y", "z"};
        case plot_curves::euler: {
            std::vector<std::string> names;
            for (char axis : d_.euler->name) names.emplace_back(1, axis);
            return names;
        }
        case plot_curves::angle: return {"from the first key"};
    }
    return {};
}

std::string rotation_values::y_label() const {
    switch (d_.curves) {
        case plot_curves::quat: return "quaternion component";
        case plot_curves::euler: return fmt::format("{} angle ({})", d_.euler->name, unit_name(d_.unit));
        case plot_curves::angle: return fmt::format("angle ({})", unit_name(d_.unit));
    }
    return "";
}

rotation_drawing drawing_of(const options& o, const std::optional<euler_seq>& own) {
    rotation_drawing d;
    d.euler = o.out_euler ? o.out_euler : o.euler ? o.euler : own;
    d.curves = o.curves.value_or(d.euler ? plot_curves::euler : plot_curves::quat);
    d.unit = o.radians ? angle_unit::radians : angle_unit::degrees;
    if (d.curves == plot_curves::euler && !d.euler)
        throw usage_error("--rep euler needs an Euler sequence: expected --out-euler SEQ or --euler SEQ");
    return d;
}

track_drawing::track_drawing(const std::string& title, const track_span& span,
                             const std::optional<euler_seq>& euler, const rotation_drawing& drawing, method how,
                             path way, bool speed)
    : span_(span), drawing_(drawing), euler_(euler), how_(how), speed_(speed), marking_(span.keys <= most_marked),
      builder_(how, way, euler),
      rotation_(rotation_panel(title, rotation_values(drawing, quat{}))),
      speeds_{title + ": angular speed", "time (s)", fmt::format("speed ({}/s)", unit_name(drawing.unit)),
              {{"speed", svg::colour::orange, {}}}, {}, {}, true, true},
      thinners_(rotation_.curves.size() + 1, svg::curve_thinner(span.first, span.last)) {}

void track_drawing::add(const key& k) {
    if (!values_) values_.emplace(drawing_, k.rotation, euler_, how_);  // the angle is from the first key
    values_->key(k);
    last_key_ = k.rotation;
    builder_.add(k);
    draw(false);
}

void track_drawing::draw(bool end) {
    segment s;
    while (builder_.pop(s, end)) {
        const segment_curve curve = s.curve();
        const double span = span_.last - span_.first;
        const double share = span > 0 ? (s.t1 - s.t0) / span * samples_across : 1;
        const auto n = static_cast<int>(std::max(std::ceil(share), 1.0));
        for (int j = 0; j < n; ++j) {
            const double h = static_cast<double>(j) / n;
            sample(j == 0 ? s.t0 : s.t0 + h * (s.t1 - s.t0), curve.at(h), &curve, h, j == 0);
        }
        last_curve_ = curve;
    }
}

void track_drawing::sample(double time, quat q, const segment_curve* curve, double h, bool at_key) {
    const std::array<double, 4> v = values_->next(time, q);
    for (std::size_t i = 0; i < rotation_.curves.size(); ++i) {
        thinners_[i].add({time, v[i]});
        if (at_key && marking_) mark(rotation_, i, {time, v[i]}, "keys");
    }
    if (speed_)
        thinners_.back().add({time, curve ? from_radians(norm(curve->rates(h).velocity), drawing_.unit) : 0});
}

std::vector<svg::panel> track_drawing::finish() {
    draw(true);
    // The last key, where the last segment ends (or the only key).
    if (last_curve_) sample(span_.last, last_curve_->at(1), &*last_curve_, 1, true);
    else sample(span_.last, last_key_, nullptr, 0, true);
    for (std::size_t i = 0; i < rotation_.curves.size(); ++i) rotation_.curves[i].points = thinners_[i].finish();
    if (!marking_) say_unmarked(rotation_, span_.keys, "keys");
    std::vector<svg::panel> panels{std::move(rotation_)};
    if (speed_) {
        speeds_.curves[0].points = thinners_.back().finish();
        panels.push_back(std::move(speeds_));
    }
    return panels;
}

void difference_plot::row(const row_difference& r) {
    auto [at, added] = tracks_.try_emplace(r.track);
    if (added) order_.push_back(r.track);
    track_rows& t = at->second;
    if (!r.angle_deg) {
        t.unmatched.push_back(r.time);
        return;
    }
    t.differences.push_back({r.time, *r.angle_deg});
    if (!r.pass()) t.failing.push_back({r.time, *r.angle_deg});
}

std::vector<svg::panel> difference_plot::panels(const std::string& prefix) const {
    std::vector<svg::panel> out;
    for (const std::string& name : order_) {
        const track_rows& t = tracks_.at(name);
        svg::panel p{prefix + (name.empty() ? "rotation difference" : name), "time (s)", "difference (deg)", {},
                     {}, {}, true, false};
        p.curves.push_back({"difference", svg::colour::blue, t.differences});
        p.levels.push_back(tolerance_level(tol_deg_));
        if (!t.failing.empty()) p.marked.push_back({"failing rows", svg::colour::vermillion, svg::mark_shape::cross, t.failing});
        if (!t.unmatched.empty()) {
            // A row in one file only has no difference: marked along the top of what is drawn.
            double top = tol_deg_;
            for (const svg::point& d : t.differences) top = std::max(top, d.y);
            svg::marks m{"in one file only", svg::colour::purple, svg::mark_shape::cross, {}};
            for (double time : t.unmatched) m.points.push_back({time, top});
            p.marked.push_back(std::move(m));
        }
        out.push_back(std::move(p));
    }
    return out;
}

void reduction_plot::begin_track(const std::string& name, const std::optional<euler_seq>& euler,
                                 const reduce_options& r) {
    name_ = name, euler_ = euler, how_ = r;
    keys_.clear(), kept_.clear();
    replay_.emplace(r.how, r.way, euler);
    replayed_ = 0;
}

// The kept keys are played as they come (each comes after the keys up to
// it), so that only their times are held.
void reduction_plot::keep(const keyrot::key& k) {
    kept_.push_back(k.time);
    replay_->add(k);
    replay(false);
}

void reduction_plot::replay(bool end) {
    segment s;
    while (replay_->pop(s, end)) {
        const segment_curve curve = s.curve();
        for (; replayed_ < keys_.size() && keys_[replayed_].time <= s.t1; ++replayed_) {
            timed& k = keys_[replayed_];
            const quat played = curve.at(std::clamp((k.time - s.t0) / (s.t1 - s.t0), 0.0, 1.0));
            k.error_deg = from_radians(geodesic_angle(played, k.rotation), angle_unit::degrees);
        }
    }
}

void reduction_plot::end_track() {
    replay(true);
    // A track held as its first key (one kept): every key against it.
    for (; replayed_ < keys_.size(); ++replayed_) {
        timed& k = keys_[replayed_];
        k.error_deg = from_radians(geodesic_angle(keys_.front().rotation, k.rotation), angle_unit::degrees);
    }
    const rotation_drawing drawing = drawing_of(o_, euler_);
    rotation_values values(drawing, keys_.front().rotation);
    const std::string title = name_.empty() ? source_ : named_by_file_ ? source_ + ": " + name_ : name_;
    svg::panel original = rotation_panel(title, values);
    svg::panel error{title + ": error of the kept keys' replay", "time (s)", "error (deg)",
                     {{"error", svg::colour::blue, {}}}, {},
                     {tolerance_level(how_.tol_deg)}, true, true};
    // Each curve thinned to its panel's columns as it is made.
    std::vector<svg::curve_thinner> thinners(original.curves.size() + 1,
                                             svg::curve_thinner(keys_.front().time, keys_.back().time));
    std::size_t next_kept = 0;
    for (const timed& k : keys_) {
        const std::array<double, 4> v = values.next(k.time, k.rotation);
        const bool kept = next_kept < kept_.size() && kept_[next_kept] == k.time;
        next_kept += kept;
        for (std::size_t i = 0; i < original.curves.size(); ++i) {
            thinners[i].add({k.time, v[i]});
            if (kept && kept_.size() <= most_marked) mark(original, i, {k.time, v[i]}, "kept keys");
        }
        thinners.back().add({k.time, k.error_deg});
    }
    for (std::size_t i = 0; i < original.curves.size(); ++i) original.curves[i].points = thinners[i].finish();
    error.curves[0].points = thinners.back().finish();
    if (kept_.size() > most_marked) say_unmarked(original, kept_.size(), "kept keys");
    panels_.push_back(std::move(original));
    panels_.push_back(std::move(error));
}

picture_file::picture_file(const std::string& path, bool fsync, std::ostream& out) : out_(out) {
    if (!is_standard_stream(path)) file_.emplace(path, commit_mode{fsync, nullptr});
}

void picture_file::write(const svg::figure& f) {
    const std::string text = svg::to_svg(f);
    if (!file_) return write_to_stream(out_, text);
    file_->write(text);
    file_->commit();
}

}  // namespace keyrot::detail
