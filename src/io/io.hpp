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

struct raw_document {
    std::vector<raw_track> tracks;  ///< in order of first appearance
    bool named = false;             ///< the input had a track column / tracks object
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

/// The keys on the lines of a key_reader whose keys each take one line
/// (CSV, NDJSON), parsed apart from each other: one parser to a thread.
class line_parser {
public:
    virtual ~line_parser() = default;
    /// The key on line `line_no`, and the name of its track; false for a line
    /// with none (blank, a comment). Throws input_error as key_reader::next.
    virtual bool parse(std::string_view line, std::size_t line_no, std::string& track, raw_key& k) = 0;
    /// Where settings differ from track to track (a JSON document's): those
    /// of the key parse() read last, valid as long as the reader. Otherwise
    /// none: the reader's hold for every key.
    virtual const key_settings* settings() const { return nullptr; }
};

/// Keys one at a time from a line-based document (CSV, NDJSON), in file
/// order, so that a long track needs no more memory than a few keys.
class key_reader {
public:
    virtual ~key_reader() = default;
    /// The next key and the name of its track ("" without tracks); false at
    /// the end. Throws input_error for a malformed line.
    virtual bool next(std::string& track, raw_key& k) = 0;
    /// Where each key takes one line: a parser for the lines of
    /// next_line(), which then stands in for next(). Otherwise none, as
    /// for NDJSON before its first key.
    virtual std::unique_ptr<line_parser> parser() const { return nullptr; }
    /// With a parser(): the next line as it is (valid until the next call)
    /// and its number; false at the end.
    virtual bool next_line(std::string_view& /*line*/, std::size_t& /*line_no*/) { return false; }
    /// The input names its tracks (a track column, "track" fields).
    virtual bool named() const = 0;
    /// Where the keys start (the CSV header), for "no keys" errors.
    virtual location start() const = 0;
    /// The settings of the track of the key next() gave last: a JSON
    /// document's own fields over the flags; for line-based input, the
    /// flags' for every key.
    virtual const key_settings& settings() const = 0;

protected:
    /// next() for a reader whose lines `parser` reads.
    bool next_parsed(line_parser& parser, std::string& track, raw_key& k) {
        std::string_view line;
        std::size_t line_no = 0;
        while (next_line(line, line_no))
            if (parser.parse(line, line_no, track, k)) return true;
        return false;
    }
};

/// For format::csv or format::ndjson, or format::json where the document
/// allows (make_json_reader). Warnings (unknown columns) go to `warn`.
std::unique_ptr<key_reader> make_key_reader(std::istream& in, format f, const read_options& opts, warnings& warn);

/// `reader`'s keys, parsed on threads of their own ahead of the caller once
/// more than a thousand have come and `worth_it()` (asked then, on the
/// caller's thread) says so: on two, a batch of lines each in turn, with
/// copies of the reader's parser() (none: no threads). The caller must not
/// use the reader's stream.
std::unique_ptr<key_reader> read_ahead(std::unique_ptr<key_reader> reader, std::function<bool()> worth_it);

/// A whole document, keys grouped into tracks by name in order of first
/// appearance. Warnings (unknown columns, say) go to `warn`.
raw_document read_document(std::istream& in, format f, const read_options& opts, warnings& warn);
raw_document read_document(std::string_view text, format f, const read_options& opts, warnings& warn);

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
