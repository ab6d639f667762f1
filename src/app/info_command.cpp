// SPDX-License-Identifier: MIT
// info: what an input holds, track by track: a summary of each, read a key
// at a time; with --segments, every segment's angle and speed as well.
#include <fmt/format.h>

#include <algorithm>
#include <ostream>
#include <utility>
#include <vector>

#include "app/commands.hpp"
#include "app/plan.hpp"
#include "io/bvh/bvh_read.hpp"
#include "io/common/layout.hpp"
#include "io/document.hpp"
#include "io/json/json.hpp"
#include "io/json/json_object.hpp"
#include "keyrot/describe.hpp"

namespace keyrot::detail {

namespace {

/// A track as info describes it: its description, and what its file says of it.
struct described_track {
    track_describer keys;
    std::optional<track_interpolation> interpolation;  ///< the file's own (glTF)
    std::optional<double> key_fps;                     ///< the rate its file or --key-fps states
    channels carried;
    bool counted = false;  ///< some key is timed by its frame number alone
};

/// An input's tracks described, in order of first appearance.
struct described_file {
    std::string source;
    format fmt = format::csv;
    std::vector<described_track> tracks;
};

/// "0.35 s (frames 42 to 43)" where the segment's keys have frame numbers, else "0.35 s (keys 42 to 43)".
std::string place(const peak& p) {
    std::string time;
    append_number(time, p.time, 6);
    if (!p.frame || !p.frame_to) return fmt::format("{} s (keys {} to {})", time, p.from, p.from + 1);
    std::string from, to;
    append_number(from, *p.frame, std::nullopt);
    append_number(to, *p.frame_to, std::nullopt);
    return fmt::format("{} s (frames {} to {})", time, from, to);
}

/// A warning for each speed spike (the first ten, and how many more).
void speed_warnings(const track_info& t, warnings& warn) {
    if (!t.speed) return;
    const speed_info& v = *t.speed;
    for (const peak& p : v.spikes) {
        std::string speed;
        append_number(speed, p.value, 0);
        warn.once(fmt::format("spike {} {}", t.name, p.from),
                  fmt::format("{}{} deg/s at {}, over {} times the speed around it: a flip, swapped joints or a "
                              "dropped marker?",
                              t.name.empty() ? "" : fmt::format("track '{}': ", t.name), speed, place(p),
                              spike_times_median));
    }
    if (v.spike_count > v.spikes.size())
        warn.once("spikes " + t.name, fmt::format("{}{} more such speeds", t.name.empty() ? "" : fmt::format("track '{}': ", t.name),
                              v.spike_count - v.spikes.size()));
}

described_file describe_file(const options& o, const input_source& src, warnings& warn) {
    described_file file{src.source(), src.detect(o.from), {}};
    track_order order;
    const auto restart = [&] { file.tracks.clear(), order.clear(); };
    const auto each = [&](const std::string& name, const key_settings& s, key&& k) {
        const auto [at, added] = order.add(name, k, src.source());
        if (added) {
            // the speed under the method in force: --method, else the file's own, else slerp
            const method how = o.how.value_or(s.interpolation ? s.interpolation->rotation : method::slerp);
            file.tracks.push_back({track_describer(name, s.euler, o.segments, how, o.way), s.interpolation, s.key_fps, {}});
        }
        described_track& t = file.tracks[at];
        t.keys.add(k);
        t.carried |= channels_of(k);
        t.counted = t.counted || (k.frame && !k.has_time);
    };
    for_each_key(src, file.fmt, reading(o, src.source()), warn, restart, each);
    for (described_track& t : file.tracks) {
        try {
            t.keys.finish();
        } catch (const spline_error& e) {
            throw error(fmt::format("{}: track '{}': {}", src.source(), t.keys.info().name, e.what()));
        }
        speed_warnings(t.keys.info(), warn);
    }
    return file;
}

/// How a track's file says its channels are played: a glTF LINEAR sampler
/// is "slerp" for a rotation (as --method names it) and "linear" for a
/// translation, scale or weights: {"rotation", "slerp"}, {"translation", "linear"}.
std::vector<std::pair<std::string_view, std::string_view>> interpolations(const described_track& t) {
    const track_interpolation& i = *t.interpolation;
    // A vector channel "played by slerp" moves in a straight line: linear.
    const auto vector = [](method how) { return how == method::slerp ? std::string_view("linear") : to_string(how); };
    std::vector<std::pair<std::string_view, std::string_view>> out{{"rotation", to_string(i.rotation)}};
    if (t.carried.translation) out.emplace_back("translation", vector(i.translation));
    if (t.carried.scale) out.emplace_back("scale", vector(i.scale));
    if (t.carried.weights) out.emplace_back("weights", vector(i.weights));
    return out;
}

std::string rep_list(const std::vector<rep>& reps) {
    std::vector<std::string_view> names;
    for (rep r : reps) names.push_back(to_string(r));
    return fmt::format("{}", fmt::join(names, ", "));
}

/// "none", "1, 5, 9", or the first ten and how many more.
std::string key_list_text(const key_list& l) {
    if (l.count == 0) return "none";
    std::string listed = fmt::format("{}", fmt::join(l.first, ", "));
    return l.count == l.first.size() ? listed : fmt::format("{}, ... ({} in all)", listed, l.count);
}

/// `bvh`: a BVH file's hierarchy and motion header (tracks[i] is joints[i]).
std::string info_text(const described_file& file, std::optional<int> precision, const bvh_source* bvh) {
    auto num = [precision](double v) {
        std::string s;
        append_number(s, v, precision.value_or(6));
        return s;
    };
    const std::size_t n_tracks = file.tracks.size();
    // (printable: a file name's control bytes must not reach a terminal raw)
    std::string out = fmt::format("{}: {} track{}, {}{}\n", printable(file.source), n_tracks, n_tracks == 1 ? "" : "s",
                                  to_string(file.fmt),
                                  bvh ? fmt::format(", {} frames at {} fps (Frame Time {})", bvh->frames, num(bvh->fps),
                                                    num(bvh->frame_time))
                                      : "");
    for (std::size_t n = 0; n < n_tracks; ++n) {
        const track_info& t = file.tracks[n].keys.info();
        out += fmt::format("{}: {} key{}, {} s to {} s, given as {}\n", t.name.empty() ? "track" : "track " + t.name,
                           t.keys, t.keys == 1 ? "" : "s", num(t.start), num(t.end), rep_list(t.given_as));
        if (bvh)
            out += fmt::format("  channels: {} (Euler {})\n", fmt::join(bvh->joints[n].channels, " "),
                               bvh->joints[n].euler.name);
        if (const std::size_t w = file.tracks[n].carried.weights)
            out += fmt::format("  morph weights: {} (w0 to w{})\n", w, w - 1);
        if (file.tracks[n].interpolation) {
            std::vector<std::string> each;
            for (const auto& [channel, how] : interpolations(file.tracks[n])) each.push_back(fmt::format("{} {}", channel, how));
            out += fmt::format("  interpolation: {}\n", fmt::join(each, ", "));
        }
        if (const described_track& d = file.tracks[n]; d.counted)
            out += d.key_fps ? fmt::format("  frame numbers: at {} fps, as stated\n", num(*d.key_fps))
                             : fmt::format("  frame numbers: at {} fps, the default (--key-fps RATE for another)\n",
                                           default_key_fps);
        if (t.keys > 1) {
            const double rate = static_cast<double>(t.keys - 1) / (t.end - t.start);
            out += t.even() ? fmt::format("  spacing: every {} s ({} keys/s)\n", num(t.shortest_gap), num(rate))
                            : fmt::format("  spacing: {} s to {} s ({} keys/s on average)\n",
                                          num(t.shortest_gap), num(t.longest_gap), num(rate));
            const segment_info& s = *t.largest;
            out += fmt::format("  largest step: {} deg, keys {} to {} ({} s to {} s), {} deg/s{}\n", num(s.angle_deg),
                               t.largest_from, t.largest_from + 1, num(t.largest_start), num(t.largest_end),
                               num(s.speed_deg_s), s.direct_long_way && t.signed_keys ? " (long way with --path direct)" : "");
        }
        if (t.speed) {
            const speed_info& v = *t.speed;
            out += fmt::format("  speed ({}): up to {} deg/s at {}, mean {} deg/s\n", to_string(v.how),
                               num(v.fastest.value), place(v.fastest), num(v.mean));
            // (slerp and step turn at one rate through a segment: no acceleration to speak of)
            if (v.how != method::slerp && v.how != method::step)
                out += fmt::format("  acceleration ({}): up to {} deg/s^2 at {}\n", to_string(v.how),
                                   num(v.most_accelerated.value), place(v.most_accelerated));
            std::vector<std::string> where;
            for (const peak& p : v.spikes) where.push_back(place(p));
            if (v.spike_count > v.spikes.size()) where.push_back(fmt::format("... ({} in all)", v.spike_count));
            out += fmt::format("  speed spikes (over {} times the speed around, turning over {} deg): {}\n",
                               spike_times_median, spike_least_deg, where.empty() ? "none" : fmt::format("{}", fmt::join(where, ", ")));
        }
        for (std::size_t i = 0; i < t.segments.size(); ++i) {
            const segment_info& s = t.segments[i];
            if (i == 0) out += "  segment  angle (deg)  speed (deg/s)\n";
            const bool long_way = s.direct_long_way && t.signed_keys;
            out += fmt::format("  {:<7}  {:<11}  {}{}\n", fmt::format("{}-{}", i, i + 1), num(s.angle_deg),
                               num(s.speed_deg_s), long_way ? "  (long way with --path direct)" : "");
        }
        if (t.quaternion_keys)
            out += fmt::format("  quaternion keys of the other sign than the one before: {}\n", key_list_text(t.flipped));
        out += fmt::format("  keys renormalised: {}\n", key_list_text(t.renormalised));
        out += fmt::format("  Euler keys within {} deg of gimbal lock: {}\n", near_gimbal_deg,
                           key_list_text(t.near_gimbal));
    }
    return out;
}

/// JSON values, each JSON already, as a JSON array: ["a", "b"].
std::string json_array(const std::vector<std::string>& quoted) { return fmt::format("[{}]", fmt::join(quoted, ", ")); }

/// {"count": 12, "first": [1, 5, ...]}: how many, and the first ten.
std::string json_key_list(const key_list& l) {
    return json_object().count("count", l.count).raw("first", fmt::format("[{}]", fmt::join(l.first, ", "))).object();
}

/// `segments`: every segment listed (--segments).
std::string info_json(const described_file& file, bool segments, const bvh_source* bvh) {
    json_object top;
    top.text("source", file.source).text("format", to_string(file.fmt));
    if (bvh) top.count("frames", bvh->frames).number("fps", bvh->fps).number("frame_time", bvh->frame_time);
    std::string tracks = "[";
    for (std::size_t n = 0; n < file.tracks.size(); ++n) {
        const described_track& d = file.tracks[n];
        const track_info& t = d.keys.info();
        std::vector<std::string> reps;
        for (rep r : t.given_as) reps.push_back(json_quote(to_string(r)));
        json_object track;
        track.text("name", t.name).count("keys", t.keys).number("start", t.start).number("end", t.end);
        track.raw("given_as", json_array(reps));
        if (d.counted) track.number("key_fps", d.key_fps.value_or(default_key_fps)).flag("key_fps_stated", d.key_fps.has_value());
        if (t.keys > 1) {
            track.number("shortest_gap", t.shortest_gap).number("longest_gap", t.longest_gap);
            track.raw("largest_segment", json_object()
                                             .count("from", t.largest_from)
                                             .number("start", t.largest_start)
                                             .number("end", t.largest_end)
                                             .number("angle", t.largest->angle_deg)
                                             .number("speed", t.largest->speed_deg_s)
                                             .object());
        }
        if (t.speed) {
            const speed_info& v = *t.speed;
            const auto at = [](const peak& p) {
                return json_object().number("value", p.value).number("time", p.time).count("from", p.from)
                    .number("frame", p.frame).number("frame_to", p.frame_to).object();
            };
            std::vector<std::string> spikes;
            for (const peak& p : v.spikes) spikes.push_back(at(p));
            track.raw("speed", json_object()
                                   .text("method", to_string(v.how))
                                   .raw("fastest", at(v.fastest))
                                   .raw("most_accelerated", at(v.most_accelerated))
                                   .number("mean", v.mean)
                                   .raw("spikes", json_object().count("count", v.spike_count).raw("first", json_array(spikes)).object())
                                   .object());
        }
        if (segments) {
            std::vector<std::string> each;
            for (const segment_info& s : t.segments)
                each.push_back(json_object()
                                   .number("angle", s.angle_deg)
                                   .number("speed", s.speed_deg_s)
                                   .raw("direct_long_way", t.signed_keys ? (s.direct_long_way ? "true" : "false") : "null")
                                   .object());
            track.raw("segments", json_array(each));
        }
        if (const std::size_t w = d.carried.weights) track.count("weights", w);
        // Only where the file states it (glTF).
        if (d.interpolation) {
            json_object each;
            for (const auto& [channel, how] : interpolations(d)) each.text(channel, how);
            track.raw("interpolation", each.object());
        }
        if (bvh) {
            std::vector<std::string> names;
            for (const std::string& c : bvh->joints[n].channels) names.push_back(json_quote(c));
            track.raw("channels", json_array(names)).text("euler", bvh->joints[n].euler.name);
        }
        track.raw("flipped", t.quaternion_keys ? json_key_list(t.flipped) : "null");
        track.raw("renormalised", json_key_list(t.renormalised)).raw("near_gimbal_lock", json_key_list(t.near_gimbal));
        tracks += (n ? ",\n" : "\n") + track.object();
    }
    return top.raw("tracks", tracks + ']').object() + '\n';
}

}  // namespace

int run_info(const options& o, std::istream& in, std::ostream& out, std::ostream& err) {
    const bool as_json = o.to == format::json || (o.output && format_of_path(*o.output) == format::json);
    std::string text;
    const std::vector<std::string> inputs = input_names(o);
    std::size_t failed = 0;
    for (const std::string& name : inputs) {
        try {
            const input_source src(name, in);
            warnings warn(err, src.source());
            const described_file file = describe_file(o, src, warn);
            const auto bvh = file.fmt == format::bvh ? read_bvh_source(*src.open(), reading(o, src.source())) : nullptr;
            text += as_json ? info_json(file, o.segments, bvh.get()) : info_text(file, o.precision, bvh.get());
        } catch (const option_error&) {  // the whole run's
            throw;
        } catch (const error& e) {
            print_error(err, e.what());
            ++failed;
        }
    }
    if (inputs.size() > 1) say_failed_files(err, failed, inputs.size());
    emit(o, text, out);
    return failed ? 2 : 0;
}

}  // namespace keyrot::detail
