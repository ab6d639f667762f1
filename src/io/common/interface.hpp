// SPDX-License-Identifier: MIT
#pragma once
// What the commands see of the formats: how keys are read (read_options,
// key_reader, raw_key_sink) and how tables are written (table_info,
// table_row, table_output). io/open.hpp opens them for a format.
#include <array>
#include <functional>
#include <istream>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "io/common/format.hpp"
#include "io/common/layout.hpp"
#include "io/common/raw_key.hpp"
#include "keyrot/track.hpp"

namespace keyrot {

class arc_frame_sink;

/// Everything a reader needs besides the text.
struct read_options {
    std::string source;      ///< file name for messages, "<stdin>" for stdin
    key_settings settings;   ///< from the flags; a document's own settings override them
    quat_order order = quat_order::wxyz;
    /// The user gave --quat-order (not the default): a document that states
    /// otherwise wins, with a warning (as for the unit: key_settings::angles_given).
    bool order_given = false;
    /// Most bytes a JSON document or a glTF file read whole may take, and a
    /// line of CSV, NDJSON or BVH: endless input (/dev/zero) ends in an
    /// error, not in all memory.
    std::size_t max_bytes = default_max_bytes;
    std::size_t max_line_bytes = default_max_line_bytes;
    /// glTF: the one animation to read, by name or index (--animation).
    std::optional<std::string> animation;
};

/// Takes a JSON document's keys as they are read, track after track, so
/// that its raw keys need not all be held at once.
class raw_key_sink {
public:
    virtual ~raw_key_sink() = default;
    /// Before each track's keys: its name, place and settings (no keys).
    virtual void begin_track(raw_track header) = 0;
    virtual void key(raw_key&& k) = 0;
};

/// Throws input_error for a track name with control characters or that is
/// not UTF-8.
void check_track_name(const std::string& name, const std::string& where);

/// A track name none of `taken` has, which it then takes: `name` itself,
/// else `name.2`, `name.3`, ... (a second BVH joint or glTF node of one
/// name). Never a '#' or a comma, which CSV readers treat apart.
std::string distinct_track_name(const std::string& name, std::set<std::string>& taken);

/// Keys one at a time from a document (CSV, NDJSON, a JSON document the
/// streaming reader takes), in file order, so that a long track needs no
/// more memory than a few keys.
class key_reader {
public:
    virtual ~key_reader() = default;
    /// The next key and the name of its track ("" without tracks); false at
    /// the end. Throws input_error for a malformed line.
    virtual bool next(std::string& track, raw_key& k) = 0;
    /// The input names its tracks (a track column, "track" fields).
    virtual bool named() const = 0;
    /// Where the keys start (the CSV header), for "no keys" errors.
    virtual location start() const = 0;
    /// The settings of the track of the key next() gave last: a JSON
    /// document's own fields over the flags; for line-based input, the
    /// flags' for every key.
    virtual const key_settings& settings() const = 0;
    /// Once next() returned false: the reader stopped short of the end of
    /// a document it does not read as read_json does (a JSON document the
    /// streaming reader does not take), and what it gave does not count:
    /// the document is to be read whole. Line-based input never is.
    virtual bool declined() const { return false; }
};

/// Frame / key time columns of a table.
enum class time_columns {
    frame_and_time,  ///< resample: both
    as_given,        ///< convert: `time`, and `frame` beside it where keys have one
    time_only,       ///< slerp: the parameter, under time_name
};

/// What a writer must know before the first row.
struct table_info {
    bool named = false;  ///< write track names
    channels carried;    ///< the channels some track carries
    time_columns times = time_columns::frame_and_time;
    bool any_frame = false;  ///< as_given: some row has a frame
    std::string_view time_name = "time";
    std::string_view rows_name = "frames";  ///< JSON: "frames", or "keys" for convert
    std::optional<double> fps;              ///< the rate `frame` counts at, where rows have frames at one rate
    std::optional<std::string_view> method;  ///< the interpolation's name, for a resampled table
    bool velocity = false, acceleration = false;  ///< rows may carry them (frame_rates)
    bool operator==(const table_info&) const = default;
};

/// A row's rotation as its values of its own, in place of the ones the
/// writer would work out of its quaternion: the input's own numbers at its
/// keys, or Euler angles on the branch of the rows before them.
struct own_rotation {
    /// In the output's representation and angle unit (quaternions (w, x,
    /// y, z); three values for rotation vectors and Euler angles).
    std::array<double, 4> values{};
    bool gimbal_lock = false;  ///< Euler angles whose third was set to 0
};

/// One output row: a sample (a resampled frame, or a key as it is), and
/// what only the writers need of it.
struct table_row : sample {
    /// The values to write, where the row has its own (text tables and
    /// BVH), held as the weights are.
    const own_rotation* own = nullptr;
    /// A CUBICSPLINE key's tangents, where the row is that key (convert),
    /// held as the weights are: a glTF output writes them beside it.
    const full_spline_key* spline = nullptr;
};
static_assert(std::is_trivially_copyable_v<table_row>);

/// A table written row by row into -o FILE (a temporary file that replaces
/// it at finish(), and is removed if finish() is never reached) or into a
/// stream. begin_track comes before each track's rows (also for a single
/// unnamed track). Large outputs are formatted on other threads and written
/// in chunks as they fill.
class table_output {
public:
    virtual ~table_output() = default;
    /// `written`: how the track's rows are to be interpolated, which a glTF
    /// output states (a table has no place for it).
    virtual void begin_track(const std::string& name, channels carried, const track_interpolation& written) = 0;
    virtual void row(const table_row& s) = 0;
    /// A row that is a sample as it is (resample's frames: the everyday row).
    virtual void frame(const sample& s) { row(table_row{s}); }
    /// Where resample's slerp and squad frames may go before their
    /// rotations are worked out (keyrot/resample.hpp), or none: through frame().
    virtual arc_frame_sink* arc_frames() { return nullptr; }
    /// Where one track's rows may be made apart from the others' (on a
    /// thread of their own): an output of that track alone, whose finish()
    /// puts it after the tracks put before it; none where this output takes
    /// its tracks in order only.
    virtual std::unique_ptr<table_output> track_apart() { return nullptr; }
    /// Closes the document and puts out what is left (then commits the file).
    virtual void finish() = 0;
};

}  // namespace keyrot
