#include "io/document.hpp"

#include <map>
#include <new>
#include <optional>

#include "ground/held_warnings.hpp"
#include "io/io_json.hpp"
#include "io/open.hpp"

namespace keyrot {
namespace {

/// Keys from a key_reader (line-based input, or a streamed JSON document),
/// parsed ahead on other threads as streamed input is. False when the
/// reader declines the document (`result` then holds nothing of it).
bool read_keys(document& result, std::istream& in, const read_options& ro, warnings& warn) {
    const auto reader = make_key_reader(in, result.fmt, ro, warn, [] { return true; });
    std::map<std::string, std::size_t> index;
    std::vector<track_builder> tracks;
    std::string name;
    raw_key raw;
    while (reader->next(name, raw)) {
        const auto [it, added] = index.emplace(name, tracks.size());
        if (added) tracks.emplace_back(name, raw.at, reader->settings());  // a JSON track's may be its own
        tracks[it->second].add(raw, warn);
    }
    if (reader->declined()) return false;
    if (tracks.empty()) throw input_error(where(result.source, reader->start()), "no keys: expected at least one key");
    for (track_builder& t : tracks) result.tracks.push_back(std::move(t).finish(warn));
    result.named = reader->named();
    return true;
}

/// A JSON document's tracks, one after another.
class json_tracks final : public raw_key_sink {
public:
    json_tracks(document& result, warnings& warn) : result_(result), warn_(warn) {}
    void begin_track(raw_track header) override {
        finish();
        current_.emplace(std::move(header.name), std::move(header.at), std::move(header.settings));
    }
    void key(raw_key&& k) override { current_->add(k, warn_); }
    void finish() {
        if (current_) result_.tracks.push_back(std::move(*current_).finish(warn_));
        current_.reset();
    }

private:
    document& result_;
    warnings& warn_;
    std::optional<track_builder> current_;
};

/// A JSON document's tracks streamed, as line-based input's are. None when
/// the reader declines the document, or meets an error there: it is then
/// read whole, which says what is wrong as read_json does (syntax anywhere
/// before content). Its warnings are held back until it is known which.
std::optional<document> read_streamed_json(const input_source& src, const read_options& ro, warnings& warn) {
    std::optional<document> result;
    with_held_warnings(warn, [&](warnings& attempt) {
        document streamed{src.source(), format::json, false, {}};
        try {
            if (!read_keys(streamed, *src.open(), ro, attempt)) return false;
        } catch (const std::bad_alloc&) {  // the parsing threads', say, which the whole reader does without
            return false;
        }
        result = std::move(streamed);
        return true;
    });
    return result;
}

}  // namespace

document read_document(std::istream& in, format f, const read_options& ro, warnings& warn) {
    document result{ro.source, f, false, {}};
    try {
        if (f != format::json) {
            read_keys(result, in, ro, warn);
            return result;
        }
        json_tracks tracks(result, warn);
        result.named = read_json(in, ro, tracks, warn);
        tracks.finish();
    } catch (const std::bad_alloc&) {  // the input is held whole: a big one can be too big
        throw error(ro.source + ": out of memory");
    }
    return result;
}

document read_document(const input_source& src, format f, const read_options& ro, warnings& warn,
                       json_reading json) {
    if (f == format::json && json == json_reading::streamed_first)
        if (std::optional<document> streamed = read_streamed_json(src, ro, warn)) return std::move(*streamed);
    return read_document(*src.open(), f, ro, warn);
}

}  // namespace keyrot
