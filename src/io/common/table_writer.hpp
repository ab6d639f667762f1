// SPDX-License-Identifier: MIT
#pragma once
// The writers of the formats, row by row into a string: what open_table
// (io/open.hpp) puts out, on formatting threads or not. Internal to io.
#include <memory>
#include <string>

#include "io/common/interface.hpp"

namespace keyrot {

/// Writes rows one at a time into `out`. begin_track comes before each
/// track's rows (also for a single unnamed track); finish closes the document.
class table_writer {
public:
    virtual ~table_writer() = default;
    virtual void begin_track(const std::string& name, channels carried) = 0;
    virtual void row(const table_row& s) = 0;
    virtual void finish() = 0;
    /// For formatting rows on several threads: a writer of the same rows into
    /// `out` that writes nothing else (no header, nothing at finish), or
    /// nullptr where a row's text depends on the rows before it (JSON).
    virtual std::unique_ptr<table_writer> row_writer(std::string& out) const = 0;
};

/// A row's rotation values; Euler output warns once about gimbal lock.
rotation_values row_values(const table_row& s, const write_options& opts, warnings& warn);

/// An angular velocity or acceleration (radians per second) in the output's
/// angle unit per second.
vec3 rate_values(vec3 radians, const write_options& opts);

/// The settings an output was written with, as the members of a JSON
/// object: a JSON document's first fields, and with --settings-line always
/// an NDJSON header line or a CSV "# keyrot" line:
/// `"fps": 24, "method": "slerp", "rep": "quat", "angles": "degrees", "quat_order": "wxyz"`
/// (fps and method when known, euler and quat_order where the rep has them).
std::string settings_members(const table_info& info, const write_options& opts);

}  // namespace keyrot
