// SPDX-License-Identifier: MIT
#pragma once
// The pictures' panels: a track's rotation curves as its method plays them
// (plot), a comparison's differences over time (compare --plot), and what
// reduce kept of a track with the error of its replay (reduce --plot).
// Drawn by io/svg.
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/app.hpp"
#include "app/row_sources.hpp"
#include "io/common/output.hpp"
#include "io/svg/figure.hpp"
#include "io/svg/thin.hpp"
#include "keyrot/compare.hpp"

namespace keyrot::detail {

/// How a rotation is drawn: as `curves` (Euler angles in `euler`'s
/// sequence), angles in `unit`.
struct rotation_drawing {
    plot_curves curves = plot_curves::quat;
    std::optional<euler_seq> euler;
    angle_unit unit = angle_unit::degrees;
};

/// How the flags draw a track whose own Euler sequence is `own`: --rep,
/// else Euler angles where a sequence is known (--out-euler, --euler, the
/// file's), else the quaternion. Throws usage_error for --rep euler without a sequence.
rotation_drawing drawing_of(const options& o, const std::optional<euler_seq>& own);

/// A rotation as a drawing's curves, one value a curve, each continuous
/// from the rotation before (a quaternion's sign; Euler angles as an Euler
/// output gives them, own_values: the keys' own where they are in the
/// drawing's sequence, on their branch between them), from the track's
/// first key `first`, its keys in sequence `euler` played by `how`.
class rotation_values {
public:
    rotation_values(const rotation_drawing& d, quat first, const std::optional<euler_seq>& euler = std::nullopt,
                    method how = method::slerp);
    /// A key, before the rotations it takes part in.
    void key(const keyrot::key& k) { euler_.key(k); }
    /// The values of the rotation at `time` (the first curves' of the four).
    std::array<double, 4> next(double time, quat q);
    /// Each curve's name in the legend.
    std::vector<std::string> labels() const;
    std::string y_label() const;

private:
    rotation_drawing d_;
    quat first_, previous_;
    own_values euler_;
    bool started_ = false;
};

/// What plot knows of a track before it draws it (from a first pass).
struct track_span {
    double first = 0, last = 0;  ///< its first and last key's times
    std::size_t keys = 0;
};

/// plot: a track drawn as its keys come, its rotation played by `how` and
/// `way`, sampled densely enough between keys to show the method's curve,
/// each curve thinned as it is sampled (memory holds what the picture
/// shows, not the track), its keys marked where they are few enough to;
/// with `speed`, its angular speed in a panel below.
class track_drawing {
public:
    track_drawing(const std::string& title, const track_span& span, const std::optional<euler_seq>& euler,
                  const rotation_drawing& drawing, method how, path way, bool speed);
    /// Keys in time order.
    void add(const key& k);
    /// Throws spline_error for a cubic track whose spline does not settle.
    std::vector<svg::panel> finish();

private:
    void draw(bool end);
    void sample(double time, quat q, const segment_curve* curve, double h, bool at_key);

    track_span span_;
    rotation_drawing drawing_;
    std::optional<euler_seq> euler_;
    method how_;
    bool speed_, marking_;
    std::optional<rotation_values> values_;
    segment_builder builder_;
    std::optional<segment_curve> last_curve_;
    quat last_key_;
    svg::panel rotation_, speeds_;
    std::vector<svg::curve_thinner> thinners_;  // the rotation's curves, then the speed
};

/// compare --plot: the rows of one answer as they are settled, and then a
/// panel per track of the rotation difference over time, the tolerance as
/// a line, the failing rows marked.
class difference_plot {
public:
    explicit difference_plot(double tol_deg) : tol_deg_(tol_deg) {}
    void row(const row_difference& r);
    /// `prefix` begins each title ("answer.csv: " where there are several answers).
    std::vector<svg::panel> panels(const std::string& prefix) const;

private:
    struct track_rows {
        std::vector<svg::point> differences, failing;
        std::vector<double> unmatched;  // the times of rows in one file only
    };
    double tol_deg_;
    std::vector<std::string> order_;
    std::map<std::string, track_rows> tracks_;
};

/// reduce --plot: each track's keys and the ones kept, as reduce meets
/// them; then a panel of its rotation with the kept keys marked, and one of
/// the replay's error at every key with the tolerance as a line.
class reduction_plot final : public reduction_observer {
public:
    /// `source` names the input; `named_by_file`: titles begin with it (one input of several).
    reduction_plot(const options& o, std::string source, bool named_by_file)
        : o_(o), source_(std::move(source)), named_by_file_(named_by_file) {}
    void begin_track(const std::string& name, const std::optional<euler_seq>& euler, const reduce_options& r) override;
    void add(const keyrot::key& k) override { keys_.push_back({k.time, k.rotation, 0}); }
    void keep(const keyrot::key& k) override;
    void end_track() override;
    void restart() override { panels_.clear(); }
    const std::vector<svg::panel>& panels() const { return panels_; }

private:
    const options& o_;
    std::string source_;
    bool named_by_file_;
    std::string name_;
    std::optional<euler_seq> euler_;
    reduce_options how_;
    struct timed {
        double time;
        quat rotation;
        double error_deg;  // of the replay, once its segment is known
    };
    /// The replay's error at the keys its segments so far reach.
    void replay(bool end);

    std::vector<timed> keys_;  // every key of the track (a track of a million keys is 48 MB)
    std::vector<double> kept_;  // the kept keys' times
    std::optional<segment_builder> replay_;  // the kept keys played as reduce plays them
    std::size_t replayed_ = 0;  // the keys whose error is known
    std::vector<svg::panel> panels_;
};

/// A picture's file (-o, --plot), opened before the work, so that a target
/// that cannot be written is said before anything else is: written and put
/// in place by write(), removed if it is never called. "-" is standard output.
class picture_file {
public:
    picture_file(const std::string& path, bool fsync, std::ostream& out);
    void write(const svg::figure& f);

private:
    std::ostream& out_;
    std::optional<output_file> file_;
};

}  // namespace keyrot::detail
