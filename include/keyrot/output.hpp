#pragma once
// Writing results so that a failure never leaves a partial file behind.
#include <string>
#include <string_view>

namespace keyrot {

/// Writes `data` to a temporary file beside `path` and renames it into
/// place, so `path` is either untouched or complete. Throws keyrot::error
/// ("cannot write 'out.csv': Permission denied") on failure.
void write_file_atomically(const std::string& path, std::string_view data);

}  // namespace keyrot
