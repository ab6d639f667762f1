// SPDX-License-Identifier: MIT
#pragma once
// What makes a track's rows from its keys (row_source), one kind per
// command: resample's frame grid, convert's keys, reduce's kept keys; and
// the facts of a document they are chosen by, gathered key by key.
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/own_values.hpp"
#include "io/common/interface.hpp"
#include "io/document.hpp"
#include "keyrot/reduce.hpp"
#include "keyrot/resample.hpp"

namespace keyrot::detail {

/// What a writer must know of a document before its first row, and what
/// each track needs before its first frame, gathered key by key.
struct document_facts {
    struct track_facts {
        std::string name;
        key first, last;
        channels carried;
        std::optional<euler_seq> euler;
        std::optional<double> key_fps;  // as stated: none, default_key_fps assumed
        std::size_t keys = 0;
        std::optional<track_interpolation> interpolation;  // the file's own
    };
    std::vector<track_facts> tracks;
    bool named = false;
    bool frames = false;     // some key has both: keyrot's own frames
    bool any_frame = false;  // some key has a frame
    bool counted = false;    // some key is timed by its frame number alone
    bool velocity = false, acceleration = false;  // some key has them (a frame of resample --velocity)

    /// Whether a key of track `name` goes on the last track.
    bool on_last_track(const std::string& name) const { return !tracks.empty() && tracks.back().name == name; }

    /// Key `k` of track `track`, whose settings are `s`.
    void add(const std::string& track, const key_settings& s, key&& k) {
        add(track, s, std::move(k), on_last_track(track));
    }
    /// The same, for a caller that has asked on_last_track(track) already
    /// (`same_track`): a name compared once a key, not twice.
    void add(const std::string& track, const key_settings& s, key&& k, bool same_track) {
        frames = frames || (k.frame && k.has_time);
        if (!same_track) tracks.push_back({track, k, k, {}, s.euler, s.key_fps, 0, s.interpolation});
        any_frame = any_frame || k.frame.has_value();
        counted = counted || (k.frame && !k.has_time);
        if (k.rates) velocity = velocity || k.rates->velocity, acceleration = acceleration || k.rates->acceleration;
        ++tracks.back().keys;
        tracks.back().carried |= channels_of(k);
        tracks.back().last = std::move(k);
    }

    /// The facts of tracks read apart from these (`later`), after them.
    void append(document_facts&& later) {
        named = named || later.named;
        frames = frames || later.frames;
        any_frame = any_frame || later.any_frame;
        counted = counted || later.counted;
        velocity = velocity || later.velocity, acceleration = acceleration || later.acceleration;
        std::move(later.tracks.begin(), later.tracks.end(), std::back_inserter(tracks));
    }

    /// The channels some track carries.
    channels carried() const {
        channels c;
        for (const track_facts& t : tracks) c |= t.carried;
        return c;
    }
};

/// The facts of a document read whole.
document_facts facts_of(const document& doc);

/// Where a row source puts a track's rows: into a table, counted (how many
/// rows the keys have made so far says whether parsing ahead pays), each
/// with the values of its own that `own` gives it (none: the writer's).
class row_sink final : public arc_frame_sink {
public:
    row_sink(table_output& out, std::size_t& count, own_values* own = nullptr)
        : out_(&out), count_(&count), arc_frames_(out.arc_frames()), own_(own && own->any() ? own : nullptr) {}
    /// A track's rows begin: of its keys in `euler`, played by `how`, on the
    /// grid of `fps` (none: a row a key).
    void begin_track(const std::optional<euler_seq>& euler, method how, std::optional<double> fps) const {
        if (own_) own_->begin_track(euler, how, fps);
    }
    /// A key the next rows are made of.
    void key(const keyrot::key& k) const {
        if (own_) own_->key(k);
    }
    void row(const table_row& r) const {
        ++*count_;
        if (const own_rotation* values = own_ ? own_->of(r.time, r.rotation) : nullptr) {
            table_row with = r;
            with.own = values;
            return out_->row(with);
        }
        out_->row(r);
    }
    /// A row that is a sample as it is (resample's frames).
    void frame(const sample& s) const {
        ++*count_;
        if (const own_rotation* values = own_ ? own_->of(s.time, s.rotation) : nullptr) {
            table_row with{s};
            with.own = values;
            return out_->row(with);
        }
        out_->frame(s);
    }
    /// Itself where the output takes slerp and squad frames whose rotations
    /// it works out (counting them as rows), else none.
    arc_frame_sink* arc_frames() { return arc_frames_ ? this : nullptr; }
    void keys(const arc_keys& k) override { arc_frames_->keys(k); }
    void frame(double frame, double time) override { ++*count_, arc_frames_->frame(frame, time); }

private:
    table_output* out_;
    std::size_t* count_;
    arc_frame_sink* arc_frames_;
    own_values* own_;
};

/// What makes a track's rows from its keys, chosen once per input:
/// resample's frame grid, or convert's keys as they are.
class row_source {
public:
    virtual ~row_source() = default;
    /// What the writer is told before the first row.
    virtual table_info table(const document_facts& d) const = 0;
    /// Checks the whole input before anything is written; warns of what it assumed.
    virtual void check(const document_facts& d, warnings& warn) const = 0;
    /// What only a whole track shows (a cubic spline that does not settle),
    /// checked key by key before anything is written: none where there is
    /// nothing to check. Its add() and finish() throw input_error.
    class track_check {
    public:
        virtual ~track_check() = default;
        virtual void add(const key& k) = 0;
        virtual void finish() = 0;
    };
    virtual std::unique_ptr<track_check> check_track(const std::string&) const { return nullptr; }
    /// Whether check_track gives every track a check (else none).
    virtual bool checks_tracks() const { return false; }
    /// In one pass: checks key `k` of track `name`, whose first key is `first`, before its rows.
    virtual void check_key(const key& first, const key& k, const std::string& name, const std::string& source) const = 0;
    /// How a glTF file is to interpolate the rows of a track whose file states `own`.
    virtual track_interpolation written(const std::optional<track_interpolation>& own) const = 0;
    /// Track `name` begins (`own`: the interpolation its file states): its rows go to `row`.
    virtual void begin_track(const std::string& name, const std::optional<euler_seq>& euler,
                             const std::optional<track_interpolation>& own, channels carried, row_sink row) = 0;
    virtual void add(const key& k) = 0;
    virtual void end_track() = 0;
    /// The rows made so far do not count: the input is read again.
    virtual void restart() {}
    /// A row source of the same settings for a track whose rows are made
    /// apart from the others' (on a thread of its own); none where a
    /// track's rows depend on the tracks before it.
    virtual std::unique_ptr<row_source> for_track_apart() const { return nullptr; }
    /// After the last track, what is to be said of them (reduce's summaries).
    virtual void report(std::ostream&, std::ostream&) const {}
};

/// resample: every frame of the grid within a track's keys. `method_given`:
/// --method overrides the interpolation a file states; `source` names the input in messages.
std::unique_ptr<row_source> make_frame_rows(const resample_options& r, bool method_given, std::string source);

/// convert: each key as it is, with its own frame or time.
std::unique_ptr<row_source> make_key_rows();

/// What reduce --plot sees of each track: its keys, and the ones kept.
class reduction_observer {
public:
    virtual ~reduction_observer() = default;
    /// Track `name` begins, reduced as `r` says.
    virtual void begin_track(const std::string& name, const std::optional<euler_seq>& euler,
                             const reduce_options& r) = 0;
    virtual void add(const key& k) = 0;
    virtual void keep(const key& k) = 0;
    virtual void end_track() = 0;
    /// What was seen does not count: the input is read again.
    virtual void restart() = 0;
};

/// reduce: the fewest of each track's keys that replay within tolerance,
/// as convert writes keys. `report_json`: --report json; `gltf`: the output
/// is a glTF file, which plays rotations LINEAR (slerp) or STEP only;
/// `watch`: told of every key and every kept one (reduce --plot), or none.
std::unique_ptr<row_source> make_reduced_rows(const reduce_options& r, bool method_given, bool report_json,
                                              std::string source, bool gltf, reduction_observer* watch = nullptr);

}  // namespace keyrot::detail
