#pragma once
// Grading: match two sets of tracks row by row and measure the differences.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "keyrot/track.hpp"

namespace keyrot {

struct tolerances {
    double rotation_deg = 0.01;  ///< geodesic angle
    double translation = 0.001;  ///< Euclidean distance, of translations and of scales
};

/// One row of the report: a key of EXPECTED, of ACTUAL, or a matched pair.
struct row_difference {
    std::string track;
    std::optional<double> frame;
    double time = 0;
    std::optional<double> angle_deg;    ///< sign-invariant geodesic angle; absent if unmatched
    std::optional<double> translation;  ///< distance, when EXPECTED has a translation and ACTUAL too
    std::optional<double> scale;        ///< the same for scales
    std::string problem;                ///< why it failed ("only in ACTUAL", ...); empty if it passed
    bool extra = false;                 ///< a row of ACTUAL that EXPECTED has not
    bool pass() const { return problem.empty(); }
};

/// Whether a row that only ACTUAL has fails the comparison (fail), or is
/// counted as extra but does not (allowed: only the rows the key asks for
/// are graded).
enum class extra_rows { fail, allowed };

struct comparison {
    std::vector<row_difference> rows;  ///< EXPECTED's order, then ACTUAL's unmatched rows
    std::size_t failed = 0;
    std::size_t matched = 0;  ///< rows in both files
    std::size_t missing = 0;  ///< rows of EXPECTED that ACTUAL has not
    std::size_t extra = 0;    ///< rows of ACTUAL that EXPECTED has not
    std::optional<std::size_t> worst;  ///< index of the largest angle among matched rows
    std::vector<std::string> missing_tracks;  ///< EXPECTED's tracks that ACTUAL has not (their rows are missing)
    std::vector<std::string> extra_tracks;    ///< ACTUAL's tracks that EXPECTED has not
    /// The first pair of tracks whose frames count at two rates (EXPECTED's,
    /// ACTUAL's), whose rows were therefore matched by time.
    std::optional<std::pair<double, double>> frame_rates;
};

/// The rate a track's frame numbers count at: for frames that carry their
/// time as well (keyrot's own resampled frames, which state no rate), the
/// rate those imply; otherwise the rate stated, or default_key_fps.
double counted_rate(const track& t);

/// Rows are matched by track name and frame when both keys have a frame and
/// both tracks' frame numbers name the same moments (the same stated rate,
/// or, where counted_rate is implied by times, grids that stay within half
/// a frame of each other), else by track and time (|dt| <= tol::match_time,
/// or either track's time rounding as stored where that is more:
/// track_interpolation::time_rounding, or 2^-24 of the time for a track
/// whose every time is a 32-bit float, as a glTF file's are, even when
/// written out as a decimal). A track and its negation (every q as -q)
/// compare equal: every angle_deg 0, failed 0.
comparison compare_tracks(const std::vector<track>& expected, const std::vector<track>& actual,
                          const tolerances& tol, extra_rows extra = extra_rows::fail);

}  // namespace keyrot
