// SPDX-License-Identifier: MIT
#pragma once
// An input read whole into tracks (what resample and convert read when
// tracks interleave or a JSON document is not streamed, and what the tests
// read), or its keys one at a time (key_stream, for_each_key: compare and
// info).
#include <functional>
#include <istream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/common/interface.hpp"
#include "io/common/source.hpp"
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

/// An input's keys one at a time, each made (make_key) as it is read, in
/// file order, without holding the input: line-based input, glTF, BVH, and
/// a JSON document the streaming reader takes. A JSON document it declines
/// says so at its end (declined()), having handed out keys that do not
/// count; the caller reads it whole (read_document) and streams that.
class key_stream {
public:
    key_stream(const input_source& src, format f, const read_options& ro, warnings& warn);
    /// The keys of a document read whole, track after track.
    explicit key_stream(const document& whole);
    /// The next key and the name of its track; false at the end. Throws
    /// input_error for a malformed key.
    bool next(std::string& track, key& k);
    /// The settings of the track of the key next() gave last.
    const key_settings& settings() const;
    /// Where the keys start, for "no keys" errors.
    location start() const;
    bool declined() const { return reader_ && reader_->declined(); }

private:
    std::unique_ptr<std::istream> stream_;
    std::unique_ptr<key_reader> reader_;
    warnings* warn_ = nullptr;
    raw_key raw_;
    const document* whole_ = nullptr;
    std::size_t track_ = 0, key_ = 0;
    key_settings settings_;  // of whole_'s current track
};

/// Tracks by name in order of first appearance, for a reader of keys one at
/// a time whose tracks may interleave: each key is checked to come after
/// its track's last (check_next).
class track_order {
public:
    /// The index of `k`'s track `name` (the next one, for a new name), and
    /// whether it is new. Throws input_error when `k` is not after the
    /// track's last key.
    std::pair<std::size_t, bool> add(const std::string& name, const key& k, const std::string& source);
    void clear() { index_.clear(), last_time_.clear(); }

private:
    std::map<std::string, std::size_t> index_;
    std::vector<double> last_time_;
};

/// Every key of `src` handed to `each(track, settings, key)` in file order,
/// streamed (key_stream); a JSON document the streaming reader declines, or
/// meets an error in, is read whole instead (its error worded as the whole
/// reader words it), after `restart()` drops what the attempt handed out,
/// whose warnings are dropped too. Returns that document read whole, if it
/// was. Throws input_error for an input without keys.
std::optional<document> for_each_key(const input_source& src, format f, const read_options& ro, warnings& warn,
                                     const std::function<void()>& restart,
                                     const std::function<void(const std::string&, const key_settings&, key&&)>& each);

}  // namespace keyrot
