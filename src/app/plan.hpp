// SPDX-License-Identifier: MIT
#pragma once
// What the commands make of the options before they read: the settings of
// reading, sampling and writing, and where inputs and output are.
#include <cstddef>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "app/app.hpp"
#include "io/common/interface.hpp"
#include "io/common/output.hpp"
#include "io/common/source.hpp"
#include "io/document.hpp"
#include "keyrot/reduce.hpp"

namespace keyrot::detail {

/// The inputs named, standard input ("-") when none is.
std::vector<std::string> input_names(const options& o);
/// A batch's closing line, where `failed` of its `files` failed: "keyrot:
/// 3 of 53 files failed"; nothing where none did.
void say_failed_files(std::ostream& err, std::size_t failed, std::size_t files);
/// The file -o names; none for standard output (no -o, or -o -).
std::optional<std::string> output_path(const options& o);

/// The key settings the flags give (a document may state its own).
key_settings settings_of(const options& o);
/// How the input that messages call `source` is read.
read_options reading(const options& o, const std::string& source);
/// How rows are written, the Euler sequence of rep::euler being --out-euler's,
/// else the input's. Throws usage_error for rep::euler without either.
write_options writing(const options& o, const std::optional<euler_seq>& input_euler);
/// Throws usage_error for --compact where the output (`out`) is not glTF,
/// and for glb bound for standard output (no `target`) that is a terminal.
void check_output_format(const options& o, format out, const std::optional<std::string>& target);
resample_options resampling(const options& o);
/// What reduce's flags make of a track (a glTF sampler's own interpolation aside).
reduce_options reducing(const options& o);

/// Text written as it is made, to -o FILE (a temporary file put in place
/// by finish()) or to `out`, a piece at a time: a long report is never
/// held whole.
class text_output {
public:
    text_output(const options& o, std::ostream& out);
    void write(std::string_view text);
    void finish();

private:
    void flush();
    std::ostream& out_;
    std::optional<output_file> file_;
    std::string pending_;
};

/// Writes `text` to -o FILE (atomically) or to `out`.
void emit(const options& o, const std::string& text, std::ostream& out);

}  // namespace keyrot::detail
