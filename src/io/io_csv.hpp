#pragma once
// CSV: a header naming the columns (any order, any case), one key per row.
#include <istream>
#include <memory>
#include <string>

#include "io/io.hpp"
#include "io/line_keys.hpp"
#include "io/table_writer.hpp"

namespace keyrot {

/// Reads the header at once; keys on demand. Throws input_error
/// "<source>:<line>: ..." for anything malformed.
std::unique_ptr<line_key_reader> make_csv_reader(std::istream& in, const read_options& opts, warnings& warn);

std::unique_ptr<table_writer> make_csv_writer(std::string& out, const table_info& info,
                                              const write_options& opts, warnings& warn);

}  // namespace keyrot
