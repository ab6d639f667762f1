// SPDX-License-Identifier: MIT
#pragma once
// CSV: a header naming the columns (any order, any case), one key per row.
#include <istream>
#include <memory>
#include <string>
#include <string_view>

#include "io/common/interface.hpp"
#include "io/common/line_keys.hpp"
#include "io/common/table_writer.hpp"

namespace keyrot {

/// Reads the header at once; keys on demand. Throws input_error
/// "<source>:<line>: ..." for anything malformed.
std::unique_ptr<line_key_reader> make_csv_reader(std::istream& in, const read_options& opts, warnings& warn);

/// The line before the header in which keyrot states its settings:
/// `# keyrot {"fps": 24, "rep": "quat", ...}` (settings_members).
inline constexpr std::string_view csv_settings_comment = "# keyrot ";

/// Appends `text` as a CSV cell: as it is, or quoted ("hip, left") where it
/// would otherwise read back as something else.
void append_csv_cell(std::string& out, std::string_view text);

std::unique_ptr<table_writer> make_csv_writer(std::string& out, const table_info& info,
                                              const write_options& opts, warnings& warn);

}  // namespace keyrot
