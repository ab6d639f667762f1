// SPDX-License-Identifier: MIT
#include "io/document.hpp"

#include <map>
#include <new>
#include <optional>

#include "ground/held_warnings.hpp"
#include "io/json/json.hpp"
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

key_stream::key_stream(const input_source& src, format f, const read_options& ro, warnings& warn)
    : stream_(src.open()), reader_(make_key_reader(*stream_, f, ro, warn, [] { return true; })), warn_(&warn) {}

key_stream::key_stream(const document& whole) : whole_(&whole) {}

bool key_stream::next(std::string& name, key& k) {
    if (reader_) {
        if (!reader_->next(name, raw_)) return false;
        k = make_key(raw_, reader_->settings(), *warn_);
        return true;
    }
    while (track_ < whole_->tracks.size() && key_ == whole_->tracks[track_].keys.size()) ++track_, key_ = 0;
    if (track_ == whole_->tracks.size()) return false;
    const keyrot::track& t = whole_->tracks[track_];
    if (key_ == 0) settings_ = {angle_unit::degrees, false, t.euler, t.key_fps, false, false, t.interpolation};
    name = t.name;
    k = t.keys[key_++];
    return true;
}

const key_settings& key_stream::settings() const { return reader_ ? reader_->settings() : settings_; }
location key_stream::start() const { return reader_ ? reader_->start() : location{}; }

std::pair<std::size_t, bool> track_order::add(const std::string& name, const key& k, const std::string& source) {
    const auto [it, added] = index_.emplace(name, last_time_.size());
    if (added) {
        last_time_.push_back(k.time);
    } else {
        if (!(k.time > last_time_[it->second])) {
            key previous;
            previous.time = last_time_[it->second];
            check_next(previous, k, source);
        }
        last_time_[it->second] = k.time;
    }
    return {it->second, added};
}

std::optional<document> for_each_key(const input_source& src, format f, const read_options& ro, warnings& warn,
                                     const std::function<void()>& restart,
                                     const std::function<void(const std::string&, const key_settings&, key&&)>& each) {
    const auto all = [&](key_stream& keys) {
        std::string name;
        key k;
        bool any = false;
        while (keys.next(name, k)) any = true, each(name, keys.settings(), std::move(k));
        if (keys.declined()) return false;
        if (!any) throw input_error(where(ro.source, keys.start()), "no keys: expected at least one key");
        return true;
    };
    if (f != format::json) {
        try {
            key_stream keys(src, f, ro, warn);
            all(keys);
        } catch (const std::bad_alloc&) {  // a line too long for the memory there is
            throw error(ro.source + ": out of memory");
        }
        return std::nullopt;
    }
    const bool streamed = with_held_warnings(warn, [&](warnings& attempt) {
        try {
            key_stream keys(src, f, ro, attempt);
            return all(keys);
        } catch (const std::bad_alloc&) {  // the parsing threads', say, which the whole reader does without
            return false;
        }
    });
    if (streamed) return std::nullopt;
    restart();
    document whole = read_document(*src.open(), f, ro, warn);
    key_stream keys(whole);
    all(keys);
    return whole;
}

}  // namespace keyrot
