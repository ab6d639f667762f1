// SPDX-License-Identifier: MIT
#pragma once
// Where --output-dir writes each input's output, checked before anything is
// written: no two inputs to one name, no output over an input.
#include <filesystem>
#include <string>
#include <vector>

#include "app/app.hpp"
#include "io/common/format.hpp"

namespace keyrot::detail {

/// Where --output-dir `dir` puts the output of input `name`: its file name,
/// with the output format's extension: ("out", "walks/a.json", csv) gives
/// "out/a.csv".
std::filesystem::path in_output_dir(const std::string& dir, const std::string& name, format out);

/// Throws usage_error, naming the inputs, when two of `inputs` would be
/// written to one name under o.output_dir, or an output would replace an
/// input (the same file, by device and inode). An input's output format
/// is known from the flags or its extension; where it is not (it would be
/// sniffed), inputs whose names differ only in extension are taken to collide.
void check_output_names(const options& o, const std::vector<std::string>& inputs);

}  // namespace keyrot::detail
