#pragma once
// Internal to the commands (src/app.cpp, transform.cpp, grading.cpp): what
// they share. Not part of keyrot's public API.
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "keyrot/app.hpp"
#include "io/io.hpp"
#include "keyrot/resample.hpp"
#include "io/source.hpp"
#include "keyrot/track.hpp"

namespace keyrot::detail {

/// The key settings the flags give (a JSON document may override them).
key_settings settings_of(const options& o);
read_options reading(const options& o, const input_source& src);
/// Throws usage_error for --rep euler without a sequence.
write_options output_settings(const options& o, const std::optional<euler_seq>& input_euler);
resample_options resampling(const options& o);

/// An input read whole: tracks in memory (compare, info, JSON input, and
/// line-based input whose tracks are interleaved).
struct input {
    std::string source;
    format fmt = format::csv;
    bool named = false;
    std::vector<track> tracks;
};
/// How load reads a JSON document: `streamed_first` tries make_json_reader
/// first, which holds only the keys (resample and convert have already
/// found that it does not take the document when they load one).
enum class json_reading { whole, streamed_first };
input load(const options& o, const input_source& src, warnings& warn, json_reading json);

/// Writes `text` to -o FILE (atomically) or to `out`.
void emit(const options& o, const std::string& text, std::ostream& out);

int run_transform(const options& o, std::istream& in, std::ostream& out, std::ostream& err);  // resample, convert
int run_slerp(const options& o, std::ostream& out, std::ostream& err);
int run_compare(const options& o, std::istream& in, std::ostream& out, std::ostream& err);
int run_info(const options& o, std::istream& in, std::ostream& out, std::ostream& err);

}  // namespace keyrot::detail
