#pragma once
// CSV: a header naming the columns (any order, any case), one key per row.
#include <memory>
#include <string>
#include <string_view>

#include "keyrot/io.hpp"

namespace keyrot {

/// Throws input_error "<source>:<line>: ..." for anything malformed.
raw_document read_csv(std::string_view text, const read_options& opts, warnings& warn);

std::unique_ptr<table_writer> make_csv_writer(std::string& out, const table_info& info,
                                              const write_options& opts, warnings& warn);

}  // namespace keyrot
