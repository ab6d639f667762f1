// SPDX-License-Identifier: MIT
#pragma once
// Readers whose keys each take a piece of text of their own (a CSV row, an
// NDJSON line, a key object of a streamed JSON document), so that the
// pieces can be parsed apart from each other: on read_ahead's threads
// (src/fast/read_ahead.hpp), behind make_key_reader. Internal to io.
#include <memory>
#include <string>
#include <string_view>

#include "io/common/interface.hpp"

namespace keyrot {

/// Where a key's text is in its input: its line (CSV, NDJSON), or its
/// array and its index there (a JSON document's keys).
struct text_place {
    std::size_t line = 0;
    std::size_t array = 0, index = 0;
};

/// Parses the pieces a line_key_reader gives, each apart from the others:
/// one parser to a thread.
class line_parser {
public:
    virtual ~line_parser() = default;
    /// The key in `text`, and the name of its track; false for a piece with
    /// none (blank, a comment). Throws input_error as key_reader::next.
    virtual bool parse(std::string_view text, const text_place& at, std::string& track, raw_key& k) = 0;
    /// Where settings differ from track to track (a JSON document's): those
    /// of the key parse() read last, valid as long as the reader. Otherwise
    /// none: the reader's hold for every key.
    virtual const key_settings* settings() const { return nullptr; }
};

class line_key_reader : public key_reader {
public:
    /// A parser for the pieces of next_line(), which then stands in for
    /// next(); none where pieces cannot yet be parsed apart (NDJSON before
    /// its first key).
    virtual std::unique_ptr<line_parser> parser() const = 0;
    /// The next piece as it is (valid until the next call) and its place;
    /// false at the end.
    virtual bool next_line(std::string_view& text, text_place& at) = 0;

protected:
    /// next() for a reader whose pieces `parser` reads.
    bool next_parsed(line_parser& parser, std::string& track, raw_key& k) {
        std::string_view text;
        text_place at;
        while (next_line(text, at))
            if (parser.parse(text, at, track, k)) return true;
        return false;
    }
};

}  // namespace keyrot
