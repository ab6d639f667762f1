#pragma once
// An input read whole into tracks: what compare and info read, what
// resample and convert read when tracks interleave or a JSON document is not
// streamed, and what the tests read.
#include <istream>
#include <string>
#include <vector>

#include "io/io.hpp"
#include "io/source.hpp"
#include "keyrot/track.hpp"

namespace keyrot {

struct document {
    std::string source;  ///< for messages
    format fmt = format::csv;
    bool named = false;  ///< the input names its tracks
    std::vector<track> tracks;  ///< in order of first appearance
};

/// Every track of `in`, keys grouped by track name. Each key is made as it
/// is read (line-based input is parsed ahead on other threads), so that the
/// raw values are never all held at once, and errors come in the input's
/// order. Throws input_error, and error "<source>: out of memory".
document read_document(std::istream& in, format f, const read_options& ro, warnings& warn);

/// How a JSON document is read: `streamed_first` tries the streaming reader
/// first, which holds only the keys where the whole document would take
/// about four times its text, and reads it whole where that declines.
enum class json_reading { whole, streamed_first };
document read_document(const input_source& src, format f, const read_options& ro, warnings& warn,
                       json_reading json);

}  // namespace keyrot
