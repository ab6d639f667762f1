#pragma once
// The writers of the formats, row by row into a string: what open_table
// (io.hpp) puts out, on formatting threads or not. Internal to io.
#include <memory>
#include <string>

#include "io/io.hpp"

namespace keyrot {

/// Writes rows one at a time into `out`. begin_track comes before each
/// track's rows (also for a single unnamed track); finish closes the document.
class table_writer {
public:
    virtual ~table_writer() = default;
    virtual void begin_track(const std::string& name, channels carried) = 0;
    virtual void row(const sample& s) = 0;
    virtual void finish() = 0;
    /// For formatting rows on several threads: a writer of the same rows into
    /// `out` that writes nothing else (no header, nothing at finish), or
    /// nullptr where a row's text depends on the rows before it (JSON).
    virtual std::unique_ptr<table_writer> row_writer(std::string& out) const = 0;
};

/// A row's rotation values; Euler output warns once about gimbal lock.
rotation_values row_values(const sample& s, const write_options& opts, warnings& warn);

/// What an output states about itself, so that it reads back with the
/// same meaning and no flags, as the members of a JSON object:
/// `"fps": 24, "method": "slerp", "rep": "quat", "angles": "degrees", "quat_order": "wxyz"`
/// (fps and method when known, euler and quat_order where the rep has them).
/// A JSON document's first fields, an NDJSON header line, a CSV "# keyrot" line.
std::string settings_members(const table_info& info, const write_options& opts);

}  // namespace keyrot
