// SPDX-License-Identifier: MIT
#pragma once
// Grading: match two sets of tracks row by row and measure the differences,
// whole (compare_tracks) or as the keys are read (comparer).
#include <algorithm>
#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "keyrot/track.hpp"

namespace keyrot {

struct tolerances {
    double rotation_deg = 0.01;  ///< geodesic angle
    /// Euclidean distance, of translations and of scales; and the largest
    /// difference of a morph weight.
    double translation = 0.001;
    /// The angular velocity's and acceleration's (deg/s, deg/s^2), where
    /// asked: rows whose the key has them (resample --velocity) compared.
    std::optional<double> velocity = std::nullopt, acceleration = std::nullopt;
};

/// One row of the report: a key of the key, of the answer, or a matched pair.
struct row_difference {
    std::string track;
    std::optional<double> frame;
    double time = 0;
    std::optional<double> angle_deg;    ///< sign-invariant geodesic angle; absent if unmatched
    std::optional<double> translation;  ///< distance, when the key has a translation and the answer too
    std::optional<double> scale;        ///< the same for scales
    std::optional<double> weights;      ///< the largest difference of a morph weight, when both have them
    std::string problem;                ///< why it failed ("only in the answer", ...); empty if it passed
    bool extra = false;                 ///< a row of the answer that the key has not
    /// |w - w'| (deg/s) and |a - a'| (deg/s^2), where asked and both have them.
    std::optional<double> velocity = std::nullopt, acceleration = std::nullopt;
    bool pass() const { return problem.empty(); }
};

/// Whether a row that only the answer has fails the comparison (fail), or is
/// counted as extra but does not (allowed: only the rows the key asks for
/// are graded).
enum class extra_rows { fail, allowed };

/// What matching needs to know of a whole track before its rows are
/// matched, learnt key by key (a first pass over a file): the rate its
/// frame numbers count at, and how precisely its times were stored.
class track_survey {
public:
    /// `key_fps`: the rate its file states; `time_rounding`: the relative
    /// rounding of its times as stored (track_interpolation::time_rounding).
    explicit track_survey(std::string name, std::optional<double> key_fps = std::nullopt, double time_rounding = 0);
    /// The survey of a track held whole.
    explicit track_survey(const track& t);
    void add(const key& k);

    const std::string& name() const noexcept { return name_; }
    std::size_t keys() const noexcept { return keys_; }
    bool any_frame() const noexcept { return any_frame_; }
    /// Whether some key carries morph weights.
    bool any_weights() const noexcept { return any_weights_; }
    /// As counted_rate(track).
    double counted_rate() const;
    /// Whether counted_rate is implied by frames that carry their times.
    bool rate_implied() const;
    /// Whether its file states the rate its frames count at.
    bool rate_stated() const noexcept { return key_fps_.has_value(); }
    /// The largest frame number's magnitude.
    double last_frame() const noexcept { return last_frame_; }
    /// The relative rounding of its times as stored: its file's own, or
    /// 2^-24 where every time is a 32-bit float.
    double rounding() const;
    /// Its times were stored as 32-bit floats and written out as the shortest
    /// decimals of their floats (a glTF file's, as keyrot writes them), each
    /// within half a unit of its float, which is within half a unit of the
    /// time: rounding() is at least a unit of a float, 2^-23.
    void stored_as_floats() noexcept { stored_rounding_ = std::max(stored_rounding_, 0x1p-23); }

private:
    std::string name_;
    std::optional<double> key_fps_;
    double stored_rounding_;
    std::size_t keys_ = 0;
    bool float32_ = true, any_frame_ = false, frame_without_time_ = false, any_weights_ = false;
    std::optional<std::pair<double, double>> timed_;  ///< the last key's (frame, time) that gives the rate
    double last_frame_ = 0;
};

/// What a comparison found, row counts and all.
struct comparison_summary {
    std::size_t compared = 0;  ///< rows reported: matched, missing and extra
    std::size_t failed = 0;
    std::size_t matched = 0;  ///< rows in both files
    std::size_t missing = 0;  ///< rows of the key that the answer has not
    std::size_t extra = 0;    ///< rows of the answer that the key has not
    std::optional<row_difference> worst;          ///< the matched row of the largest angle (the first of equals)
    std::optional<row_difference> first_failure;  ///< the first failing row reported
    std::vector<std::string> missing_tracks;  ///< the key's tracks that the answer has not (their rows are missing)
    std::vector<std::string> extra_tracks;    ///< the answer's tracks that the key has not
    /// The first pair of tracks whose frames count at two rates (the key's,
    /// the answer's), whose rows were therefore matched by time.
    std::optional<std::pair<double, double>> frame_rates;
    bool weights = false;  ///< some track of the key carries morph weights
};

/// Matches the keys of two files as they are read, holding only the keys
/// that wait for the other file to reach their time, and hands each row
/// to a sink as it is settled: in time order within a track.
///
/// Rows are matched by track name and frame when both keys have a frame and
/// both tracks' frame numbers name the same moments (the same stated rate,
/// or, where counted_rate is implied by times, grids that stay within half
/// a frame of each other), else by track and time (|dt| <= tol::match_time,
/// or either track's time rounding as stored where that is more:
/// track_survey::rounding). Tracks are paired by name, but a file of one
/// unnamed track and a file of one track of any name are the same track
/// (rows carry the key's name). A track and its negation (every q as -q)
/// compare equal: every angle_deg 0, failed 0.
class comparer {
public:
    using row_sink = std::function<void(const row_difference&)>;
    /// The surveys of both files' tracks (in file order), taken before.
    comparer(const std::vector<track_survey>& key_tracks, const std::vector<track_survey>& answer_tracks, const tolerances& tol,
             extra_rows extra, row_sink row);
    /// A key of the key's (or the answer's) track `track`: within a track,
    /// times strictly increase.
    void from_key(const std::string& track, key k);
    void from_answer(const std::string& track, key k);
    /// How many keys of each file wait for the other file's.
    std::size_t waiting_key() const noexcept { return waiting_[0]; }
    std::size_t waiting_answer() const noexcept { return waiting_[1]; }
    /// The tracks missing from either file and the frame rates are known
    /// from the start; the counts grow as rows are settled.
    const comparison_summary& summary() const noexcept { return summary_; }
    /// Settles the keys still waiting (no key of the other file can match them).
    const comparison_summary& finish();

private:
    struct pairing {
        bool in_key = false, in_answer = false, by_frame = false;
        double rounding = 0;
        std::deque<key> waiting[2];  ///< the key's, the answer's
    };
    void add(int side, const std::string& track, key&& k);
    void settle(const std::string& name, pairing& p);
    void put(row_difference r);
    row_difference matched(const std::string& name, const key& e, const key& a) const;
    row_difference unmatched(const std::string& name, const key& k, int side) const;

    tolerances tol_;
    extra_rows extra_;
    row_sink row_;
    std::unordered_map<std::string, pairing> pairs_;
    std::vector<std::string> order_;  ///< the key's tracks, then the answer's own
    std::optional<std::pair<std::string, std::string>> renamed_;  ///< the answer's one track, paired with the key's
    std::size_t waiting_[2] = {0, 0};
    comparison_summary summary_;
};

/// A comparison of tracks held whole, with every row.
struct comparison : comparison_summary {
    std::vector<row_difference> rows;  ///< track by track of the key, in time order; then the answer's own tracks
};

/// The rate a track's frame numbers count at: for frames that carry their
/// time as well (keyrot's own resampled frames, which state no rate), the
/// rate those imply; otherwise the rate stated, or default_key_fps.
double counted_rate(const track& t);

/// The comparer's rows of two files held whole.
comparison compare_tracks(const std::vector<track>& key_tracks, const std::vector<track>& answer_tracks,
                          const tolerances& tol, extra_rows extra = extra_rows::fail);

}  // namespace keyrot
