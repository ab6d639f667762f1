// SPDX-License-Identifier: MIT
#include "io/json/json.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <array>
#include <set>
#include <utility>
#include <vector>
#include <string_view>

#include <nlohmann/json.hpp>

#include "ground/text.hpp"
#include "io/common/line_reader.hpp"
#include "io/json/flat_json.hpp"
#include "io/json/json_keys.hpp"
#include "io/json/json_members.hpp"

namespace keyrot {
namespace {

// Members in the document's order: tracks come out in input order.
using json = nlohmann::ordered_json;

using detail::join_path;

/// Deeper nesting than this is refused before parsing, so that a hostile
/// document cannot exhaust the parser's stack.
constexpr int max_depth = 64;

/// A nlohmann-json value with flat_json::value's queries, so that one
/// reader serves both.
class dom_value {
public:
    explicit dom_value(const json& j) : j_(&j) {}
    std::string_view type_name() const { return j_->type_name(); }
    bool is_null() const { return j_->is_null(); }
    bool is_number() const { return j_->is_number(); }
    bool is_string() const { return j_->is_string(); }
    bool is_array() const { return j_->is_array(); }
    bool is_object() const { return j_->is_object(); }
    double number() const { return j_->get<double>(); }
    std::string_view string() const { return j_->get_ref<const std::string&>(); }
    std::size_t size() const { return j_->size(); }
    dom_value operator[](std::size_t i) const { return dom_value((*j_)[i]); }
    std::optional<dom_value> member(std::string_view name) const {
        const auto it = j_->find(name);
        return it == j_->end() ? std::nullopt : std::optional(dom_value(*it));
    }
    template <class F>
    void elements(F&& f) const {
        for (const json& e : *j_) f(dom_value(e));
    }
    template <class F>
    void members(F&& f) const {
        for (const auto& [name, value] : j_->items()) f(std::string_view(name), dom_value(value));
    }

private:
    const json* j_;
};

/// Line (1-based) of a byte offset, for parse errors.
std::size_t line_of(std::string_view text, std::size_t byte) {
    byte = std::min(byte, text.size());
    return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(byte), '\n'));
}

void check_depth(std::string_view text, std::string_view source, std::size_t first_line) {
    int depth = 0;
    bool in_string = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (in_string) {
            if (c == '\\') ++i;
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > max_depth)
                throw input_error(where(source, first_line + line_of(text, i) - 1),
                                  fmt::format("JSON nested deeper than {} levels: expected a keyframe document", max_depth));
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

/// Refuses a name that appears twice in one object, which nlohmann-json
/// would let the second replace the first (flat_json declines such text).
/// The message names the object by its path (tracks.hip.keys[3]), and by
/// its line where the text is one line (an NDJSON line, say): the parser's
/// events do not say where in the text they are. A pass of its own over
/// the text's events (SAX), before the document is built: nlohmann-json
/// 3.11's parser with a callback looks through a container's members at
/// the end of each object in it, which is quadratic in a long array of
/// keys.
class unique_names {
public:
    unique_names(std::string_view source, std::string_view text, std::size_t first_line)
        : source_(source), line_(text.find('\n') == std::string_view::npos ? first_line : 0) {}

    bool null() { return element(); }
    bool boolean(bool) { return element(); }
    bool number_integer(json::number_integer_t) { return element(); }
    bool number_unsigned(json::number_unsigned_t) { return element(); }
    bool number_float(json::number_float_t, const json::string_t&) { return element(); }
    bool string(json::string_t&) { return element(); }
    bool binary(json::binary_t&) { return element(); }
    bool start_object(std::size_t) { return open(false); }
    bool start_array(std::size_t) { return open(true); }
    bool end_object() { return close(); }
    bool end_array() { return close(); }
    bool key(json::string_t& name) {
        container& object = open_.back();
        object.current = name;
        if (!object.names.insert(name).second) throw twice(name);
        return true;
    }
    /// Throws what the parser found, as parsing into a document would.
    template <class Exception>
    bool parse_error(std::size_t, const std::string&, const Exception& e) {
        throw e;
    }

private:
    struct container {
        bool array;
        std::size_t elements = 0;       // an array's, so far
        std::set<std::string> names{};  // an object's, so far
        std::string current{};          // an object's latest name
    };

    bool element() {
        if (!open_.empty() && open_.back().array) ++open_.back().elements;
        return true;
    }
    bool open(bool array) {
        element();
        open_.push_back({array});
        return true;
    }
    bool close() {
        open_.pop_back();
        return true;
    }

    input_error twice(const std::string& name) const {
        std::string path;  // of the innermost object, from the outermost
        for (std::size_t i = 0; i + 1 < open_.size(); ++i)
            path = open_[i].array ? fmt::format("{}[{}]", path, open_[i].elements - 1)
                                  : join_path(path, open_[i].current);
        const std::string message =
            fmt::format("'{}' appears twice: expected each name once in an object", name.substr(0, 40));
        if (!line_) return input_error(where(source_, path.empty() ? "document" : path), message);
        return input_error(path.empty() ? where(source_, line_) : where(where(source_, line_), path), message);
    }

    std::string_view source_;
    std::size_t line_;  // 0: the text has several lines
    std::vector<container> open_;
};

/// "source:line:column" of a byte offset, so that an error in a long line
/// can be found.
std::string place_of(std::string_view text, std::size_t byte, std::string_view source, std::size_t first_line) {
    byte = std::min(byte, text.size());
    const std::size_t line_start = byte == 0 ? 0 : text.rfind('\n', byte - 1) + 1;  // (npos + 1 == 0)
    return fmt::format("{}:{}", where(source, first_line + line_of(text, byte) - 1), byte - line_start + 1);
}

/// Whether `text`, the start of a document, has a syntax error before its
/// end (which no more text could mend).
bool broken_before_end(std::string_view text) {
    try {
        [[maybe_unused]] const json parsed = json::parse(text.begin(), text.end());
    } catch (const json::parse_error& e) {
        return e.byte < text.size();
    } catch (const json::exception&) {  // (a number beyond a double: said when the whole document is read)
    }
    return false;
}

}  // namespace

json parse_json_text(std::string_view text, std::string_view source, std::size_t first_line) {
    check_depth(text, source, first_line);
    try {
        unique_names names(source, text, first_line);
        json::sax_parse(text.begin(), text.end(), &names);
        return json::parse(text.begin(), text.end());
    } catch (const json::parse_error& e) {
        if (first_line == 1 && looks_like_utf16(text.substr(0, 4))) throw input_error(std::string(source), utf16_message);
        std::string what = e.what();
        // "[json.exception.parse_error.101] parse error at line 1, column 5: ..." -> the part after ": "
        const auto colon = what.find(": ");
        if (colon != std::string::npos) what = what.substr(colon + 2);
        throw input_error(place_of(text, e.byte == 0 ? 0 : e.byte - 1, source, first_line), "invalid JSON: " + what);
    } catch (const json::out_of_range& e) {
        // A number too large for a double: "number overflow parsing '1e999'".
        const std::string what = e.what();
        const auto quote = what.find('\'');
        const std::string token = quote == std::string::npos ? "" : what.substr(quote + 1, what.size() - quote - 2);
        const std::size_t at = token.empty() ? 0 : text.find(token);
        throw input_error(where(source, first_line + line_of(text, at == std::string_view::npos ? 0 : at) - 1),
                          fmt::format("number '{}' is out of range: expected a finite number", token.substr(0, 40)));
    }
}

bool could_begin_json(std::string_view start, std::string_view openers) {
    start = without_bom(start);
    const auto first = start.find_first_not_of(" \t\r\n");
    return first == std::string_view::npos ||
           (openers.find(start[first]) != std::string_view::npos && !broken_before_end(start));
}

namespace {

using detail::apply_fields;
using detail::key_object_reader;
using detail::settings_object;

/// A track object ({"keys": [...]}, {"frames": [...]}) or a bare array of keys.
template <class Value>
void read_track(Value j, std::string name, const std::string& path, key_settings settings, quat_order order,
                const read_options& opts, raw_key_sink& sink, warnings& warn) {
    const std::string where = keyrot::where(opts.source, path.empty() ? "document" : path);
    apply_fields(j, settings, order, where, path.empty() ? settings_object::document : settings_object::track, opts, warn);
    std::optional<Value> keys = j;
    std::string field;
    if (j.is_object()) {
        const auto with_keys = j.member("keys"), with_frames = j.member("frames");
        if (with_keys.has_value() == with_frames.has_value())
            throw input_error(where, with_keys ? "both 'keys' and 'frames': expected one"
                                               : "expected 'keys', 'frames' or 'tracks'");
        field = with_keys ? "keys" : "frames";
        keys = with_keys ? with_keys : with_frames;
    }
    const std::string keys_path = field.empty() ? path : join_path(path, field);
    if (!keys->is_array())
        throw input_error(where, fmt::format("'{}': expected an array of keys, got {}", field.empty() ? name : field,
                                             keys->type_name()));
    sink.begin_track(raw_track{std::move(name), location{0, keys_path.empty() ? "document" : keys_path}, settings});
    std::size_t index = 0;
    keys->elements([&](Value key) {
        const location at{0, fmt::format("{}[{}]", keys_path, index++)};
        sink.key(key_object_reader(key, opts.source, at, order).read());
    });
}

/// A bare array of keys that name their tracks, as a table's records do
/// (pandas' to_json(orient="records") of a table with a track column):
/// each track's keys in their order, the tracks in the order they first
/// appear. False where the keys name no tracks.
template <class Value>
bool read_named_keys(Value keys, const key_settings& settings, quat_order order, const read_options& opts,
                     raw_key_sink& sink) {
    if (!keys.is_array() || keys.size() == 0 || !keys[0].is_object() || !keys[0].member("track")) return false;
    std::vector<std::string> names;
    std::map<std::string, std::vector<std::size_t>> of_track;
    std::size_t index = 0;
    keys.elements([&](Value key) {
        const location at{0, fmt::format("[{}]", index)};
        const auto track = key.is_object() ? key.member("track") : std::nullopt;
        if (!track)
            throw input_error(where(opts.source, at), "some keys have a 'track' and some do not: expected all or none");
        std::string name = key_object_reader(key, opts.source, at, order).track_name(*track);
        check_track_name(name, where(opts.source, at));
        auto [it, added] = of_track.try_emplace(name);
        if (added) names.push_back(name);
        it->second.push_back(index++);
    });
    for (const std::string& name : names) {
        sink.begin_track(raw_track{name, location{0, "document"}, settings});
        for (const std::size_t i : of_track[name]) {
            const location at{0, fmt::format("[{}]", i)};
            sink.key(key_object_reader(keys[i], opts.source, at, order).read());
        }
    }
    return true;
}

/// Returns whether the document names its tracks.
template <class Value>
bool read_json_value(Value j, const read_options& opts, raw_key_sink& sink, warnings& warn) {
    key_settings settings = opts.settings;
    quat_order order = opts.order;
    const auto tracks = j.is_object() ? j.member("tracks") : std::nullopt;
    if (tracks) {
        const std::string where = keyrot::where(opts.source, "document");
        apply_fields(j, settings, order, where, settings_object::document, opts, warn);
        if (!tracks->is_object())
            throw input_error(where, fmt::format("'tracks': expected an object of named tracks, got {}", tracks->type_name()));
        if (tracks->size() == 0) throw input_error(where, "'tracks' is empty: expected at least one track");
        tracks->members([&](std::string_view name_view, Value value) {
            const std::string name(name_view);
            check_track_name(name, where);
            read_track(value, name, "tracks." + name, settings, order, opts, sink, warn);
        });
        return true;
    }
    if (!j.is_object() && !j.is_array())
        throw input_error(opts.source, fmt::format("expected a JSON object or array, got {}", j.type_name()));
    if (read_named_keys(j, settings, order, opts, sink)) return true;
    read_track(j, "", "", settings, order, opts, sink, warn);
    return false;
}

}  // namespace

bool read_json(std::istream& in, const read_options& opts, raw_key_sink& sink, warnings& warn) {
    std::string text;
    text.reserve(static_cast<std::size_t>(std::max<std::streamsize>(0, in.rdbuf()->in_avail())));
    std::array<char, std::size_t{1} << 16> chunk;
    while (const auto got = in.rdbuf()->sgetn(chunk.data(), chunk.size())) {
        if (text.empty()) {
            // Not JSON from its first character or within its first block
            // (random bytes, /dev/zero): said now, as reading it all would
            // say it, rather than after reading all there is.
            const std::string_view start = without_bom(std::string_view(chunk.data(), static_cast<std::size_t>(got)));
            if (!could_begin_json(start, "{[")) parse_json_text(start, opts.source, 1);
        }
        if (text.size() + static_cast<std::size_t>(got) > opts.max_bytes)
            throw input_error(opts.source, fmt::format("JSON document longer than {} bytes (--max-bytes N raises the limit)",
                                                       opts.max_bytes));
        text.append(chunk.data(), static_cast<std::size_t>(got));
    }
    flat_json flat;
    if (flat.parse(text)) return read_json_value(flat.root(), opts, sink, warn);
    return read_json_value(dom_value(parse_json_text(text, opts.source, 1)), opts, sink, warn);
}

namespace {

/// Whether an NDJSON line's object is a header of settings, as keyrot
/// writes first ({"fps": 24, "rep": "quat", "angles": "degrees"}), rather
/// than a key: it has neither a time nor a rotation.
template <class Value>
bool is_header(Value j) {
    if (!j.is_object()) return false;
    for (const std::string_view field : time_members)
        if (j.member(field)) return false;
    for (const std::string_view field : rotation_members)
        if (field != rotation_member(rep::euler) && j.member(field)) return false;
    const auto euler = j.member(rotation_member(rep::euler));  // also a setting: a sequence's name
    return !euler || euler->is_string();
}

/// The keys on NDJSON lines, each line apart from the others, once the
/// first key has settled whether lines name their tracks: the reader's own
/// parser, and copies of it on read_ahead's threads.
class ndjson_lines final : public line_parser {
public:
    /// `header`: the first line's settings, if it had them.
    ndjson_lines(std::string source, quat_order order, std::string header = "")
        : source_(std::move(source)), order_(order), header_(std::move(header)) {}
    /// Whether lines have a "track"; none before the first key.
    std::optional<bool> named() const noexcept { return named_; }

    bool parse(std::string_view line, const text_place& at, std::string& track, raw_key& k) override {
        const std::size_t line_no = at.line;
        // The same header again is two of keyrot's outputs one after the other (cat a.ndjson b.ndjson).
        if (trim(line).empty() || (!header_.empty() && trim(line) == header_)) return false;
        if (fast_.parse(line)) read(fast_.root(), line_no, track, k);
        else read(dom_value(parse_json_text(line, source_, line_no)), line_no, track, k);
        return true;
    }

private:
    template <class Value>
    void read(Value j, std::size_t line_no, std::string& track, raw_key& k) {
        const auto where = [&] { return keyrot::where(source_, line_no); };
        const auto track_field = j.is_object() ? j.member("track") : std::nullopt;
        if (!named_) named_ = track_field.has_value();
        if (track_field.has_value() != *named_) {
            if (is_header(j))
                throw input_error(where(), "a header line with other settings than the first: expected the lines of one "
                                           "document (keyrot outputs made with other settings cannot be joined)");
            throw input_error(where(), "some lines have a 'track' and some do not: expected all or none");
        }
        track.clear();
        key_object_reader keys(j, source_, location{line_no, {}}, order_);
        if (track_field) {
            track = keys.track_name(*track_field);
            check_track_name(track, where());
        }
        k = keys.read();
    }

    std::string source_;
    quat_order order_;
    std::string header_;
    std::optional<bool> named_;
    flat_json fast_{detail::max_key_values};  // most lines; the rest, and all errors, by nlohmann-json
};

class ndjson_reader final : public line_key_reader {
public:
    ndjson_reader(std::istream& in, const read_options& opts, warnings& warn)
        : lines_(in, opts.max_line_bytes, opts.source), settings_(opts.settings), keys_(opts.source, opts.order) {
        std::string_view line;
        bool found = false;
        while (!found && lines_.next(line)) found = !trim(line).empty();
        if (!found) return;
        // The first line is a header when it parses as one; anything else
        // is left to the key parser, which words the error.
        flat_json fast;
        std::optional<json> slow;
        const bool parsed = fast.parse(line);
        if (!parsed) slow = json::parse(line.begin(), line.end(), nullptr, false);
        const bool header = parsed ? is_header(fast.root()) : !slow->is_discarded() && is_header(dom_value(*slow));
        if (!header) {
            lines_.put_back();  // a key, read with the header test
            return;
        }
        const std::string where = keyrot::where(opts.source, lines_.number());
        quat_order order = opts.order;
        if (parsed) apply_fields(fast.root(), settings_, order, where, settings_object::header, opts, warn);
        else apply_fields(dom_value(parse_json_text(line, opts.source, lines_.number())), settings_, order, where,
                          settings_object::header, opts, warn);
        keys_ = ndjson_lines(opts.source, order, std::string(trim(line)));
    }

    bool named() const override { return keys_.named().value_or(false); }
    location start() const override { return {}; }
    const key_settings& settings() const override { return settings_; }

    bool next(std::string& track, raw_key& k) override { return next_parsed(keys_, track, k); }

    bool next_line(std::string_view& line, text_place& at) override {
        if (!lines_.next(line)) return false;
        at.line = lines_.number();
        return true;
    }

    /// Only once a key has said whether lines name their tracks: copies
    /// that each settled it on their own lines could miss a line that
    /// breaks the rule.
    std::unique_ptr<line_parser> parser() const override {
        if (!keys_.named()) return nullptr;
        return std::make_unique<ndjson_lines>(keys_);
    }

private:
    line_reader lines_;
    key_settings settings_;
    ndjson_lines keys_;
};

}  // namespace

std::unique_ptr<line_key_reader> make_ndjson_reader(std::istream& in, const read_options& opts, warnings& warn) {
    return std::make_unique<ndjson_reader>(in, opts, warn);
}

}  // namespace keyrot
