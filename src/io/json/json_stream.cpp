// SPDX-License-Identifier: MIT
// A JSON document's keys as they arrive, block by block, for resample and
// convert: a long track in a few keys' memory, as CSV and NDJSON are read.
// Only documents laid out as keyrot and most tools write them are taken;
// for the rest the caller reads the document whole (read_json).
#include <fmt/format.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "io/json/flat_json.hpp"
#include "io/json/json_keys.hpp"
#include "io/json/json_stream.hpp"

namespace keyrot {
namespace {

/// The document's text, read in blocks and consumed token by token: only
/// the value being read (a key, a setting) is held, not what came before.
/// Text it does not take (a value longer than it holds, what is not JSON)
/// declines the document: from then on, nothing is taken.
class json_text {
public:
    /// At most `max_held` bytes of one value are held: a longer one is declined.
    json_text(std::istream& in, std::size_t max_held) : in_(in), max_held_(max_held) {}

    bool declined() const noexcept { return declined_; }
    /// For text the reader does not take; returns false.
    bool decline() noexcept {
        declined_ = true;
        return false;
    }

    /// The next character that is not white space, not taken; 0 at the end,
    /// once declined, and for a NUL byte, which is no JSON either (at_end()
    /// tells them apart).
    char peek() {
        for (std::size_t skipped = 0; !declined_; skipped += buf_.size()) {
            for (; at_ < buf_.size(); ++at_)
                if (!is_space(buf_[at_])) return buf_[at_];
            if (skipped > max_held_) decline();  // endless white space: the whole reader's limit says so
            else if (!fill()) return 0;
        }
        return 0;
    }
    /// Nothing but white space is left.
    bool at_end() {
        peek();
        return !declined_ && at_ == buf_.size();
    }
    /// Takes `c`, which must come next; false (declined) if it does not.
    bool take(char c) {
        if (peek() != c) return decline();
        ++at_;
        return true;
    }
    /// A string (a member name), taken, its escapes decoded; none if
    /// declined (what nlohmann-json would refuse: the whole reader words it).
    std::optional<std::string> string() {
        if (!take('"')) return std::nullopt;
        bool escaped = false;  // the byte after a backslash
        for (std::size_t i = at_;; ++i) {
            if (i == buf_.size()) {
                const std::size_t offset = i - at_;
                if (!fill()) return decline(), std::nullopt;
                i = at_ + offset;
            }
            const auto c = static_cast<unsigned char>(buf_[i]);
            if (escaped) {
                escaped = false;
            } else if (c == '\\') {
                escaped = true;
            } else if (c < 0x20) {
                return decline(), std::nullopt;
            } else if (c == '"') {
                std::string s;
                if (!append_json_string(std::string_view(buf_.data() + at_, i - at_), s)) return decline(), std::nullopt;
                at_ = i + 1;
                return s;
            }
        }
    }
    /// The text of the value that starts here, taken: a scalar, or an array
    /// or object to its closing bracket, valid until the next call; none if
    /// declined.
    std::optional<std::string_view> value() {
        const char first = peek();
        if (declined_) return std::nullopt;
        if (first == '{') {  // a key, most often: to its first '}', if it holds no other object and ends no string
            const auto* begin = buf_.data() + at_;
            if (const auto* close = static_cast<const char*>(std::memchr(begin, '}', buf_.size() - at_))) {
                int opens = 0, quotes = 0, escapes = 0;
                for (const auto* c = begin; c != close; ++c) {
                    opens += *c == '{';
                    quotes += *c == '"';
                    escapes += *c == '\\';
                }
                if (opens == 1 && quotes % 2 == 0 && escapes == 0)
                    return take_until(at_ + static_cast<std::size_t>(close - begin) + 1);
            }
        }
        int depth = 0;
        bool in_string = false, escaped = false;  // escaped: the byte after a backslash
        for (std::size_t i = at_;;) {
            // Most characters are digits, letters, signs and points: a look-up each.
            while (!escaped && i < buf_.size() && kind_of(buf_[i]) == kind::plain) ++i;
            if (i == buf_.size()) {
                const std::size_t offset = i - at_;
                if (!fill()) {
                    if (depth != 0 || in_string || declined_) return decline(), std::nullopt;
                    return take_until(buf_.size());
                }
                i = at_ + offset;
                continue;
            }
            if (escaped) {  // flat_json decodes it, or declines
                escaped = false;
                ++i;
                continue;
            }
            switch (kind_of(buf_[i])) {
                case kind::escape:
                    if (!in_string) return decline(), std::nullopt;
                    escaped = true;
                    break;
                case kind::quote: in_string = !in_string; break;
                case kind::open: depth += !in_string; break;
                case kind::close:
                    if (in_string) break;
                    if (depth == 0) return take_until(i);  // the end of the container holding a scalar
                    --depth;
                    break;
                case kind::stop:
                    if (depth == 0 && !in_string) return take_until(i);
                    break;
                case kind::plain: break;
            }
            ++i;
            if (depth == 0 && !in_string) return take_until(i);  // a string, or a container, ends
        }
    }

private:
    /// What a character means to value().
    enum class kind : std::uint8_t { plain, quote, escape, open, close, stop };
    static kind kind_of(char c) noexcept {
        static constexpr auto kinds = [] {
            std::array<kind, 256> k{};
            k['"'] = kind::quote, k['\\'] = kind::escape, k['['] = k['{'] = kind::open, k[']'] = k['}'] = kind::close;
            k[','] = k[' '] = k['\t'] = k['\n'] = k['\r'] = kind::stop;
            return k;
        }();
        return kinds[static_cast<unsigned char>(c)];
    }
    static bool is_space(char c) noexcept { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
    std::string_view take_until(std::size_t end) {
        const std::string_view v(buf_.data() + at_, end - at_);
        at_ = end;
        return v;
    }
    /// Drops the text taken and reads a block more; false at the end, or
    /// declined when a value would be longer than max_held_.
    bool fill() {
        buf_.erase(0, at_);
        at_ = 0;
        if (buf_.size() > max_held_) return decline();  // the whole reader says what the limit is
        const std::size_t size = buf_.size();
        buf_.resize(size + block);
        const auto got = in_.rdbuf()->sgetn(buf_.data() + size, static_cast<std::streamsize>(block));
        buf_.resize(size + static_cast<std::size_t>(got));
        return got > 0;
    }

    static constexpr std::size_t block = std::size_t{1} << 16;
    std::istream& in_;
    std::size_t max_held_;
    std::string buf_;
    std::size_t at_ = 0;
    bool declined_ = false;
};

/// A track's keys array, as the keys in it are read: its settings and names.
struct key_array {
    std::string track, path;  // path: "tracks.hip.keys", as read_json names it
    key_settings settings;
    quat_order order;
};

/// The arrays of a document, in order, added as the reader comes to them
/// and read by the parsers on read_ahead's threads: a deque, so that what
/// they hold stays in place.
struct key_arrays {
    explicit key_arrays(std::string from) : source(std::move(from)) {}
    const std::string source;  // for messages
    std::mutex mutex;
    std::deque<key_array> arrays;  // under mutex
    std::atomic<bool> declined{false};  // a key's text flat_json does not take
};

/// Keys, each parsed from its own text: the reader's parser, and copies on
/// read_ahead's threads.
class json_keys final : public line_parser {
public:
    explicit json_keys(std::shared_ptr<key_arrays> arrays) : arrays_(std::move(arrays)) {}
    json_keys(const json_keys& other) : json_keys(other.arrays_) {}

    /// The key whose text is `text`, at `place` (its array's number, and its
    /// number in the array); false, declining the document, for text
    /// flat_json does not take.
    bool parse(std::string_view text, const text_place& place, std::string& track, raw_key& k) override {
        if (place.array != number_) {
            const std::lock_guard lock(arrays_->mutex);
            array_ = &arrays_->arrays[place.array];
            number_ = place.array;
        }
        // A bare array's keys that name their tracks (a table's records) are
        // grouped by track, which only the whole document shows.
        if (!key_.parse(text) || (array_->path.empty() && key_.root().member("track"))) {
            arrays_->declined = true;
            return false;
        }
        const fmt::format_int index(place.index);
        location at{0, array_->path};
        at.path.append("[").append(index.data(), index.size()).append("]");
        k = detail::key_object_reader(key_.root(), arrays_->source, std::move(at), array_->order).read();
        track = array_->track;
        return true;
    }
    const key_settings* settings() const override { return &array_->settings; }

private:
    std::shared_ptr<key_arrays> arrays_;
    std::size_t number_ = SIZE_MAX;
    const key_array* array_ = nullptr;  // arrays_'s number_
    flat_json key_{detail::max_key_values};
};

/// Walks the document: {"keys" | "frames": [...], ...}, a bare array of
/// keys, or {"tracks": {"name": {...} | [...], ...}, ...}. What read_json
/// reads differently, or only once the whole text is known, is declined: a
/// setting ("angles", "euler", "quat_order", "fps") after the keys it
/// applies to, "tracks" beside "keys", a repeated name, a track without
/// keys, anything flat_json declines: next() then returns false, and
/// declined() true. Errors, too, are left to read_json, which reports them in
/// its own order.
class json_stream_reader final : public line_key_reader {
public:
    json_stream_reader(std::istream& in, const read_options& opts, warnings& warn)
        : text_(in, opts.max_bytes), opts_(opts), warn_(warn), document_(object::kind::document, "", "", opts.settings, opts.order),
          arrays_(std::make_shared<key_arrays>(opts.source)), keys_(arrays_) {
        if (text_.peek() == '[') {
            text_.take('[');
            begin_keys(document_, "", "");
        } else if (text_.take('{')) {
            open_.push_back(&document_);
        }
    }

    bool next(std::string& track, raw_key& k) override {
        std::string_view text;
        text_place place;
        return next_line(text, place) && keys_.parse(text, place, track, k);
    }

    /// The next key's text, and its place: its array's number, and its
    /// number in the array. False at the end, and once declined.
    bool next_line(std::string_view& text, text_place& place) override {
        while (!declined()) {
            if (in_keys_ && text_.peek() != ']') {
                if (count_ > 0 && !text_.take(',')) return false;
                const std::optional<std::string_view> key = text_.value();
                if (!key) return false;
                text = *key;
                place.array = arrays_begun_ - 1;
                place.index = count_++;
                return true;
            }
            if (in_keys_) {
                text_.take(']');
                if (count_ == 0) text_.decline();
                in_keys_ = false;
            } else if (!open_.empty()) {
                member();
            } else {
                if (!text_.at_end()) text_.decline();  // text after the document
                return false;
            }
        }
        return false;
    }
    bool declined() const override { return text_.declined() || arrays_->declined; }

    std::unique_ptr<line_parser> parser() const override { return std::make_unique<json_keys>(keys_); }

    bool named() const override { return named_; }
    location start() const override { return {}; }  // (no keys: declined)
    const key_settings& settings() const override { return settings_; }

private:
    /// An object being read, and what its members have set.
    struct object {
        enum class kind { document, tracks, track };
        object(kind t, std::string track, std::string at, const key_settings& s, quat_order o)
            : type(t), name(std::move(track)), path(std::move(at)), settings(s), order(o) {}
        kind type;
        std::string name, path;  // a track's
        key_settings settings;   // what it inherits, then its own fields over them
        quat_order order;
        std::set<std::string> members;
        std::string fields = "{";  // its own settings, as a JSON object
        bool keys = false;         // its keys (tracks) have begun
    };
    /// Reads the next member of the innermost open object, or closes it
    /// (unless declined).
    void member() {
        object& o = *open_.back();
        if (text_.peek() == '}') {
            text_.take('}');
            if (!o.keys) text_.decline();  // no keys, no tracks
            return open_.pop_back();
        }
        if (!o.members.empty() && !text_.take(',')) return;
        std::optional<std::string> name = text_.string();
        if (!name || !text_.take(':')) return;
        if (!o.members.insert(*name).second) return void(text_.decline());
        if (o.type == object::kind::tracks) return begin_track(o, std::move(*name));
        const bool keys = name == "keys" || name == "frames";
        if (keys || (o.type == object::kind::document && name == "tracks")) {
            if (o.keys || !apply_fields(o)) return void(text_.decline());
            o.keys = true;
            if (keys) {
                if (text_.take('[')) begin_keys(o, o.path, *name);
            } else if (text_.take('{')) {
                named_ = true;
                open_.push_back(&tracks_.emplace(object::kind::tracks, "", "", o.settings, o.order));
            }
            return;
        }
        const std::optional<std::string_view> value = text_.value();
        // (Checked all the same: the document must be valid JSON.)
        if (!value || !other_.parse(*value)) return void(text_.decline());
        if (name == "angles" || name == "euler" || name == "quat_order" || name == "fps") {
            if (o.keys) return void(text_.decline());  // it would change keys already read
            o.fields += fmt::format("{}\"{}\": {}", o.fields.size() > 1 ? ", " : "", *name, *value);
        } else if (!detail::descriptive_field(*name)) {
            unknown_field(*name, where(opts_.source, o.path.empty() ? "document" : o.path), o.settings,
                          warn_);
        }
    }

    /// A member of "tracks": a track object, or a bare array of keys.
    void begin_track(object& tracks, std::string name) {
        check_track_name(name, where(opts_.source, "document"));
        tracks.keys = true;
        object& track = track_.emplace(object::kind::track, name, "tracks." + name, tracks.settings, tracks.order);
        if (text_.peek() == '[') {
            text_.take('[');
            begin_keys(track, track.path, "");
        } else if (text_.take('{')) {
            open_.push_back(&track);
        }
    }

    /// The settings `o` has read over those it inherits, as read_json
    /// applies them; false for fields flat_json does not take.
    bool apply_fields(object& o) {
        o.fields += '}';
        flat_json fields;
        if (!fields.parse(o.fields)) return false;
        detail::apply_fields(fields.root(), o.settings, o.order, opts_.source, detail::settings_object::header, opts_,
                             warn_);
        return true;
    }

    void begin_keys(const object& owner, const std::string& path, const std::string& field) {
        settings_ = owner.settings;
        key_array keys{owner.name, field.empty() ? path : detail::join_path(path, field), owner.settings, owner.order};
        {
            const std::lock_guard lock(arrays_->mutex);
            arrays_->arrays.push_back(std::move(keys));
        }
        ++arrays_begun_;
        in_keys_ = true;
        count_ = 0;
    }

    json_text text_;
    read_options opts_;
    warnings& warn_;
    object document_;
    std::optional<object> tracks_, track_;
    std::vector<object*> open_;  // innermost last
    bool named_ = false;
    std::shared_ptr<key_arrays> arrays_;
    json_keys keys_;  // the reader's own parser
    std::size_t arrays_begun_ = 0;
    bool in_keys_ = false;    // within an array of keys
    std::size_t count_ = 0;   // its keys so far
    key_settings settings_;   // its settings
    flat_json other_;
};

}  // namespace

std::unique_ptr<line_key_reader> make_json_reader(std::istream& in, const read_options& opts, warnings& warn) {
    return std::make_unique<json_stream_reader>(in, opts, warn);
}

}  // namespace keyrot
