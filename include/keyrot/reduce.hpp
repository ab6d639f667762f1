// SPDX-License-Identifier: MIT
#pragma once
// Key reduction: the fewest of a track's keys that, interpolated as the
// track is played, stay within a tolerance of every key.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "keyrot/interpolate.hpp"
#include "keyrot/track.hpp"

namespace keyrot {

struct reduce_options {
    method how = method::slerp;
    path way = path::shortest;
    /// How translations, scales and morph weights are interpolated, where
    /// not as `how` says: step holds, any other method is linear (resample_options').
    std::optional<method> translation_how = std::nullopt, scale_how = std::nullopt, weights_how = std::nullopt;
    double tol_deg = 0.01;           ///< geodesic angle, sign-invariant
    /// Distance, for translations and scales; and the largest difference of a morph weight.
    double tol_translation = 0.001;
};

/// What reducing a track kept, and the largest errors it allowed.
struct reduce_summary {
    std::size_t keys = 0, kept = 0;
    double worst_deg = 0, worst_translation = 0;  ///< at the keys dropped
};

/// Reduces one track whose keys arrive one at a time. The kept keys come out
/// through `keep`, in order and unchanged: always the first; the last too,
/// unless every key is within tolerance of the first (the track is then its
/// first key, held). The guarantee: the kept keys, interpolated with
/// opts.how as resample plays them, are within opts.tol_deg and
/// opts.tol_translation of every key at its time. Keys are kept greedily:
/// from a kept key, the farthest next key that keeps the guarantee for
/// every key between, found by doubling the stretch, then halving between
/// the last good and the first bad one. Memory holds the keys since the
/// last kept one, at most max_stretch of them (squad, whose curve near a
/// key depends on the kept keys on both sides: the track).
class track_reducer {
public:
    /// Throws option_error for method::euler without a sequence, and for
    /// method::cubicspline (its tangents belong to the keys it has).
    track_reducer(const reduce_options& opts, const std::optional<euler_seq>& seq, std::string source,
                  std::function<void(const key&)> keep);
    /// Times strictly increasing (check_next). Throws input_error, naming
    /// the key in `source`, for a CUBICSPLINE key.
    void add(const key& k);
    void finish();
    const reduce_summary& summary() const { return summary_; }

private:
    struct errors {
        bool ok = true;
        double deg = 0, translation = 0;
        std::size_t bad = 0;  // where not ok: the key farthest out of tolerance (of those looked at)
    };
    /// The errors at keys `from` + 1 .. `to` - 1 of keys_ played from the
    /// kept keys `from` and `to` (squad: with `before` and `after` too); up
    /// to the first key out of tolerance, or with `whole` all of them. A
    /// rotation error plainly below `floor` degrees (and the tolerance)
    /// counts as 0: deg is the largest only where that is more than floor.
    errors between(std::size_t from, std::size_t to, std::optional<std::size_t> before = std::nullopt,
                   std::optional<std::size_t> after = std::nullopt, bool whole = false, double floor = 0) const;
    /// What a stretch tried was found to hold: whether every key is within
    /// tolerance (between(0, to).ok), the largest rotation error (exact
    /// where it is more than the summary's largest so far; where deg_exact
    /// is false, a bound at least as large) and the largest translation
    /// error (where ok).
    struct reach {
        bool ok = false;
        double deg = 0;
        bool deg_exact = true;
        double translation = 0;
    };
    /// The probes' question: for slerp, most keys are answered without the
    /// exact curve (core/arc_screen.hpp), but at the search's `last` probe,
    /// which is kept if it holds.
    reach reaches(std::size_t to, bool last) const;
    /// The errors of the stretch kept, from keys_[0] to keys_[good_], found `r`:
    /// exact where they could change what the summary says.
    errors kept_errors(const reach& r) const;
    /// The segment from key `from` to key `to` as played (squad: with `before` and `after`).
    segment segment_between(std::size_t from, std::size_t to, std::optional<std::size_t> before = std::nullopt,
                            std::optional<std::size_t> after = std::nullopt) const;
    /// Key k's largest distance, by translation, scale or weights, from keys a and b played at h.
    double translation_error(const key& a, const key& b, double h, const key& k) const;
    void advance(bool end);
    void emit(std::size_t i, const errors& e);
    void reduce_squad();

    /// The most keys a kept key reaches (memory holds them): a stretch of
    /// more (136 s at 120 Hz) keeps a key where it ends.
    static constexpr std::size_t max_stretch = std::size_t{1} << 14;

    reduce_options opts_;
    std::optional<euler_seq> seq_;
    std::string source_;
    std::function<void(const key&)> keep_;
    mutable segment_builder builder_;  // between()'s, kept for its memory
    double sin_half_tol_;              // what the probes' screens of the tolerance share
    std::vector<key> keys_;            // from the last kept key (squad: the whole track)
    std::size_t good_ = 0;             // the farthest key known to be reachable from keys_[0]
    reach good_reach_;                 // what reaching it found
    key first_;
    double from_first_deg_ = 0, from_first_translation_ = 0;  // the farthest any key is from the first, while held_
    bool held_ = false;                                       // every key so far within tolerance of the first
    std::vector<key> pending_;  // kept after the first while held_: out once the track moves
    reduce_summary summary_;
};

}  // namespace keyrot
