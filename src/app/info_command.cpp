// info: what an input holds, track by track.
#include <fmt/format.h>

#include <algorithm>
#include <ostream>
#include <utility>
#include <vector>

#include "app/commands.hpp"
#include "app/plan.hpp"
#include "io/bvh.hpp"
#include "io/document.hpp"
#include "io/layout.hpp"
#include "keyrot/describe.hpp"

namespace keyrot::detail {

namespace {

std::string index_list(const std::vector<std::size_t>& v) {
    return v.empty() ? std::string("none") : fmt::format("{}", fmt::join(v, ", "));
}

std::string rep_list(const std::vector<rep>& reps) {
    std::vector<std::string_view> names;
    for (rep r : reps) names.push_back(to_string(r));
    return fmt::format("{}", fmt::join(names, ", "));
}

/// How a track's file says its channels are played: a glTF LINEAR sampler
/// is "slerp" for a rotation (as --method names it) and "linear" for a
/// translation or scale: {"rotation", "slerp"}, {"translation", "linear"}.
std::vector<std::pair<std::string_view, std::string_view>> interpolations(const track& t) {
    const track_interpolation& i = *t.interpolation;
    channels carried;
    for (const key& k : t.keys) carried |= channels_of(k);
    // A vector channel "played by slerp" moves in a straight line: linear.
    const auto vector = [](method how) { return how == method::slerp ? std::string_view("linear") : to_string(how); };
    std::vector<std::pair<std::string_view, std::string_view>> out{{"rotation", to_string(i.rotation)}};
    if (carried.translation) out.emplace_back("translation", vector(i.translation));
    if (carried.scale) out.emplace_back("scale", vector(i.scale));
    return out;
}

/// `bvh`: a BVH file's hierarchy and motion header (tracks[i] is joints[i]).
std::string info_text(const document& doc, const std::vector<track_info>& infos, std::optional<int> precision,
                      const bvh_source* bvh) {
    auto num = [precision](double v) {
        std::string s;
        append_number(s, v, precision.value_or(6));
        return s;
    };
    // (printable: a file name's control bytes must not reach a terminal raw)
    std::string out = fmt::format("{}: {} track{}, {}{}\n", printable(doc.source), infos.size(),
                                  infos.size() == 1 ? "" : "s", to_string(doc.fmt),
                                  bvh ? fmt::format(", {} frames at {} fps (Frame Time {})", bvh->frames, num(bvh->fps),
                                                    num(bvh->frame_time))
                                      : "");
    for (std::size_t n = 0; n < infos.size(); ++n) {
        const track_info& t = infos[n];
        out += fmt::format("{}: {} key{}, {} s to {} s, given as {}\n", t.name.empty() ? "track" : "track " + t.name,
                           t.keys, t.keys == 1 ? "" : "s", num(t.start), num(t.end), rep_list(t.given_as));
        if (bvh)
            out += fmt::format("  channels: {} (Euler {})\n", fmt::join(bvh->joints[n].channels, " "),
                               bvh->joints[n].euler.name);
        if (doc.tracks[n].interpolation) {
            std::vector<std::string> each;
            for (const auto& [channel, how] : interpolations(doc.tracks[n])) each.push_back(fmt::format("{} {}", channel, how));
            out += fmt::format("  interpolation: {}\n", fmt::join(each, ", "));
        }
        for (std::size_t i = 0; i < t.segments.size(); ++i) {
            const segment_info& s = t.segments[i];
            if (i == 0) out += "  segment  angle (deg)  speed (deg/s)\n";
            const bool long_way = s.direct_long_way && t.signed_keys;
            out += fmt::format("  {:<7}  {:<11}  {}{}\n", fmt::format("{}-{}", i, i + 1), num(s.angle_deg),
                               num(s.speed_deg_s), long_way ? "  (long way with --path direct)" : "");
        }
        if (t.signed_keys) out += fmt::format("  keys flipped by --path shortest: {}\n", index_list(t.flipped));
        out += fmt::format("  keys renormalised: {}\n", index_list(t.renormalised));
        out += fmt::format("  Euler keys within {} deg of gimbal lock: {}\n", near_gimbal_deg, index_list(t.near_gimbal));
    }
    return out;
}

std::string info_json(const document& doc, const std::vector<track_info>& infos, const bvh_source* bvh) {
    auto num = [](double v) {
        std::string s;
        append_number(s, v, std::nullopt);
        return s;
    };
    auto list = [](const std::vector<std::size_t>& v) { return fmt::format("[{}]", fmt::join(v, ", ")); };
    std::string out = "{\"source\": " + json_quote(doc.source) + ", \"format\": \"" +
                      std::string(to_string(doc.fmt)) + "\", ";
    if (bvh)
        out += fmt::format("\"frames\": {}, \"fps\": {}, \"frame_time\": {}, ", bvh->frames, num(bvh->fps),
                           num(bvh->frame_time));
    out += "\"tracks\": [";
    for (std::size_t n = 0; n < infos.size(); ++n) {
        const track_info& t = infos[n];
        std::vector<std::string> reps, segments;
        for (rep r : t.given_as) reps.push_back(fmt::format("\"{}\"", to_string(r)));
        for (const segment_info& s : t.segments)
            segments.push_back(fmt::format("{{\"angle\": {}, \"speed\": {}, \"direct_long_way\": {}}}", num(s.angle_deg),
                                           num(s.speed_deg_s), t.signed_keys ? fmt::format("{}", s.direct_long_way) : "null"));
        // Only where the file states it (glTF).
        std::string interpolation;
        if (doc.tracks[n].interpolation) {
            std::vector<std::string> each;
            for (const auto& [channel, how] : interpolations(doc.tracks[n]))
                each.push_back(fmt::format("\"{}\": \"{}\"", channel, how));
            interpolation = fmt::format(", \"interpolation\": {{{}}}", fmt::join(each, ", "));
        }
        if (bvh) {
            std::vector<std::string> names;
            for (const std::string& c : bvh->joints[n].channels) names.push_back(json_quote(c));
            interpolation += fmt::format(", \"channels\": [{}], \"euler\": \"{}\"", fmt::join(names, ", "),
                                         bvh->joints[n].euler.name);
        }
        out += fmt::format(
            "{}\n{{\"name\": {}, \"keys\": {}, \"start\": {}, \"end\": {}, \"given_as\": [{}], \"segments\": [{}], "
            "\"flipped\": {}, \"renormalised\": {}, \"near_gimbal_lock\": {}{}}}",
            n ? "," : "", json_quote(t.name), t.keys, num(t.start), num(t.end), fmt::join(reps, ", "),
            fmt::join(segments, ", "), t.signed_keys ? list(t.flipped) : "null", list(t.renormalised), list(t.near_gimbal),
            interpolation);
    }
    out += "]}\n";
    return out;
}

}  // namespace

int run_info(const options& o, std::istream& in, std::ostream& out, std::ostream& err) {
    const bool as_json = o.to == format::json || (o.output && format_of_path(*o.output) == format::json);
    std::string text;
    int status = 0;
    for (const std::string& name : input_names(o)) {
        try {
            const input_source src(name, in);
            warnings warn(err, src.source());
            const document doc = read_input(o, src, warn);
            std::vector<track_info> infos;
            for (const track& t : doc.tracks) infos.push_back(describe(t));
            const auto bvh = doc.fmt == format::bvh ? read_bvh_source(*src.open(), reading(o, src.source())) : nullptr;
            text += as_json ? info_json(doc, infos, bvh.get()) : info_text(doc, infos, o.precision, bvh.get());
        } catch (const usage_error&) {
            throw;
        } catch (const error& e) {
            print_error(err, e.what());
            status = 2;
        }
    }
    emit(o, text, out);
    return status;
}

}  // namespace keyrot::detail
