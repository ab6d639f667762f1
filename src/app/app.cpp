#include "keyrot/app.hpp"

#include <map>
#include <new>
#include <optional>
#include <ostream>

#include "app/commands.hpp"
#include "io/io_json.hpp"
#include "io/output.hpp"

namespace keyrot {
namespace detail {

key_settings settings_of(const options& o) {
    return {o.radians ? angle_unit::radians : angle_unit::degrees, o.euler, o.key_fps.value_or(o.fps), o.strict};
}

read_options reading(const options& o, const input_source& src) {
    read_options ro;
    ro.source = src.source();
    ro.settings = settings_of(o);
    ro.order = o.order;
    ro.given.angles = o.radians;
    ro.given.key_fps = o.key_fps.has_value();
    ro.max_bytes = o.max_bytes;
    return ro;
}

write_options output_settings(const options& o, const std::optional<euler_seq>& input_euler) {
    write_options w;
    w.representation = o.representation;
    w.angles = o.out_angles.value_or(o.radians ? angle_unit::radians : angle_unit::degrees);
    w.order = o.order;
    w.precision = o.precision;
    if (w.representation == rep::euler) {
        // --out-euler, else the input's sequence (--euler or the document's own).
        w.euler = o.out_euler ? o.out_euler : input_euler;
        if (!w.euler) throw usage_error("--rep euler needs an Euler sequence: expected --out-euler SEQ or --euler SEQ");
    }
    return w;
}

resample_options resampling(const options& o) {
    resample_options r;
    r.fps = o.fps;
    r.how = o.how;
    r.way = o.way;
    r.max_frames = o.max_frames;
    return r;
}

namespace {

// Each key is made as it is read, so that the raw values are never all
// held at once (they took more room than the keys), and errors come in the
// input's order.

/// Line-based input (its tracks may interleave), parsed ahead on other
/// threads as streamed input is.
void load_lines(input& result, std::istream& in, const read_options& ro, warnings& warn) {
    const auto reader = read_ahead(make_key_reader(in, result.fmt, ro, warn), [] { return true; });
    std::map<std::string, std::size_t> index;
    std::vector<track_builder> tracks;
    std::string name;
    raw_key raw;
    while (reader->next(name, raw)) {
        const auto [it, added] = index.emplace(name, tracks.size());
        if (added) tracks.emplace_back(name, raw.at, reader->settings());  // a JSON track's may be its own
        tracks[it->second].add(raw, warn);
    }
    if (tracks.empty()) throw input_error(where(result.source, reader->start()), "no keys: expected at least one key");
    for (track_builder& t : tracks) result.tracks.push_back(std::move(t).finish(warn));
    result.named = reader->named();
}

/// A JSON document's keys streamed (make_json_reader), as line-based
/// input's are: they take their own room, where the document read whole
/// takes about four times its text. False when the reader does not take the
/// document, or finds an error: it is then read whole, which says what is
/// wrong as it always has. Its warnings are held back until it is known which.
bool load_streamed_json(input& result, const input_source& src, const read_options& ro, warnings& warn) {
    return with_held_warnings(warn, [&](warnings& attempt) {
        input streamed{result.source, result.fmt, false, {}};
        try {
            load_lines(streamed, *src.open(), ro, attempt);
        } catch (const std::bad_alloc&) {  // the parsing threads', say, which the whole reader does without
            return false;
        }
        result = std::move(streamed);
        return true;
    });
}

/// A JSON document's tracks, one after another.
class json_tracks final : public raw_key_sink {
public:
    json_tracks(input& result, warnings& warn) : result_(result), warn_(warn) {}
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
    input& result_;
    warnings& warn_;
    std::optional<track_builder> current_;
};

}  // namespace

input load(const options& o, const input_source& src, warnings& warn, json_reading json) {
    input result{src.source(), src.detect(o.from), false, {}};
    try {
        const read_options ro = reading(o, src);
        if (result.fmt == format::json && json == json_reading::streamed_first &&
            load_streamed_json(result, src, ro, warn))
            return result;
        const auto stream = src.open();
        if (result.fmt != format::json) {
            load_lines(result, *stream, ro, warn);
            return result;
        }
        json_tracks tracks(result, warn);
        result.named = read_json(*stream, ro, tracks, warn);
        tracks.finish();
    } catch (const std::bad_alloc&) {  // the input is held whole: a big one can be too big
        throw error(src.source() + ": out of memory");
    }
    return result;
}

/// Writes `text` to -o FILE (atomically) or to `out`.
void emit(const options& o, const std::string& text, std::ostream& out) {
    if (o.output && *o.output != "-") write_file_atomically(*o.output, text);
    else write_to_stream(out, text);
}

}  // namespace detail

int run(const options& o, std::istream& in, std::ostream& out, std::ostream& err) {
    switch (o.cmd) {
        case command::resample:
        case command::convert: return detail::run_transform(o, in, out, err);
        case command::slerp: return detail::run_slerp(o, out, err);
        case command::compare: return detail::run_compare(o, in, out, err);
        case command::info: return detail::run_info(o, in, out, err);
    }
    return 2;
}

}  // namespace keyrot
