#pragma once
// The file formats and what is common to their readers and writers: the
// document a reader returns and the row-by-row writer interface.
#include <functional>
#include <istream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "keyrot/format.hpp"
#include "keyrot/frame.hpp"
#include "io/layout.hpp"
#include "keyrot/track.hpp"

namespace keyrot {

/// Everything a reader needs besides the text.
struct read_options {
    std::string source;      ///< file name for messages, "<stdin>" for stdin
    key_settings settings;   ///< from the flags; a document's own settings override them
    quat_order order = quat_order::wxyz;
    /// Which settings the user gave as flags (not defaults): a document
    /// that states otherwise wins, with a warning.
    struct {
        bool angles = false, key_fps = false;
    } given;
    /// Most bytes a CSV or NDJSON line, or a JSON document read whole, may
    /// take: endless input (/dev/zero) ends in an error, not in all memory.
    std::size_t max_bytes = default_max_bytes;
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

/// Throws input_error for a track name with control characters.
void check_track_name(const std::string& name, const std::string& where);

/// Keys one at a time from a line-based document (CSV, NDJSON), in file
/// order, so that a long track needs no more memory than a few keys.
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
};

/// For format::csv or format::ndjson, or format::json where the document
/// allows (make_json_reader). Warnings (unknown columns) go to `warn`. With
/// `parse_ahead`, keys are parsed on threads of their own ahead of the
/// caller once more than a thousand have come and `parse_ahead()` (asked
/// once, then, on the caller's thread) says it pays; the caller must not
/// use `in` meanwhile.
std::unique_ptr<key_reader> make_key_reader(std::istream& in, format f, const read_options& opts, warnings& warn,
                                            std::function<bool()> parse_ahead = nullptr);

/// Frame / key time columns of a table.
enum class time_columns {
    frame_and_time,  ///< resample: both
    as_given,        ///< convert: JSON writes each key's own; CSV `frame` if all keys have one, `time` if any has one
    time_only,       ///< slerp: the parameter, under time_name
};

/// What a writer must know before the first row.
struct table_info {
    bool named = false;        ///< write track names
    bool translation = false;  ///< some track has a translation
    time_columns times = time_columns::frame_and_time;
    bool all_frames = false;  ///< as_given: every row has a frame
    bool any_time = true;     ///< as_given: some row has a time
    std::string_view time_name = "time";
    std::string_view rows_name = "frames";  ///< JSON: "frames", or "keys" for convert
    std::optional<double> fps;              ///< the rate `frame` counts at, when rows have frames
    std::optional<std::string_view> method;  ///< the interpolation's name, for a resampled table
    bool operator==(const table_info&) const = default;
};

/// Writes rows one at a time into `out`. begin_track comes before each
/// track's rows (also for a single unnamed track); finish closes the document.
class table_writer {
public:
    virtual ~table_writer() = default;
    virtual void begin_track(const std::string& name, bool has_translation) = 0;
    virtual void row(const sample& s) = 0;
    virtual void finish() = 0;
    /// For formatting rows on several threads: a writer of the same rows into
    /// `out` that writes nothing else (no header, nothing at finish), or
    /// nullptr where a row's text depends on the rows before it (JSON).
    virtual std::unique_ptr<table_writer> row_writer(std::string& out) const = 0;
};

/// A row's rotation values; Euler output warns once about gimbal lock.
rotation_values row_values(const sample& s, const write_options& opts, warnings& warn);

/// `text` as a JSON string literal, quotes included. Throws input_error for invalid UTF-8.
std::string json_quote(std::string_view text);

/// What an output states about itself, so that it reads back with the
/// same meaning and no flags, as the members of a JSON object:
/// `"fps": 24, "method": "slerp", "rep": "quat", "angles": "degrees", "quat_order": "wxyz"`
/// (fps and method when known, euler and quat_order where the rep has them).
/// A JSON document's first fields, an NDJSON header line, a CSV "# keyrot" line.
std::string settings_members(const table_info& info, const write_options& opts);

/// Euler output warns once about gimbal lock through `warn`.
std::unique_ptr<table_writer> make_writer(format f, std::string& out, const table_info& info,
                                          const write_options& opts, warnings& warn);

}  // namespace keyrot
