// SPDX-License-Identifier: MIT
// libFuzzer target, differential: the bytes choose valid tracks, which the
// harness writes itself as a CSV table, a JSON document, NDJSON, JSON and
// NDJSON records, and as a BVH take. Every reader must read the same keys
// to the bit (BVH: the rotations of its Euler angles); the tracks written
// by keyrot as glTF (.glb and .gltf) must read back to them within a
// float's precision. Then one command (convert, resample or reduce) runs
// on the CSV or the BVH into another format and representation: its output, read
// back with no flags (but the Euler sequence, which keyrot states only in
// a JSON document), must mean what its CSV of quaternions means. Any
// difference is a finding.
#include <fmt/format.h>
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "command.hpp"
#include "io/document.hpp"
#include "keyrot/convert.hpp"

namespace {

using namespace keyrot;

/// A number as the harness writes it: its text, and what that text reads as.
struct number {
    std::string text;
    double value = 0;
};

/// A decimal with up to `decimals` digits after the point, from `whole`.
number decimal(long long whole, int decimals) {
    std::string text = fmt::format("{}", whole);
    if (decimals > 0) {
        const bool negative = whole < 0;
        std::string digits = text.substr(negative ? 1 : 0);
        if (digits.size() <= static_cast<std::size_t>(decimals))
            digits.insert(0, static_cast<std::size_t>(decimals) + 1 - digits.size(), '0');
        digits.insert(digits.size() - static_cast<std::size_t>(decimals), ".");
        text = (negative ? "-" : "") + digits;
    }
    return {text, std::stod(text)};
}

number shortest(double v) { return {fmt::format("{}", v), v}; }

struct generated_key {
    number time;
    std::array<number, 4> quat;         // w, x, y, z
    std::array<number, 3> translation;  // where the tracks have them
};

struct generated_track {
    std::string name;
    std::vector<generated_key> keys;
};

struct generated {
    std::vector<generated_track> tracks;
    bool translations = false;
};

/// Track names a reader must take as they are: a space, a dot, non-ASCII.
constexpr std::array<std::string_view, 5> names = {"hip", "Left Leg", "köpf", "j.2", "Ω"};

generated generate(FuzzedDataProvider& in) {
    generated g;
    g.translations = in.ConsumeBool();
    const std::size_t n_tracks = in.ConsumeIntegralInRange<std::size_t>(1, 3);
    const std::size_t first = in.ConsumeIntegralInRange<std::size_t>(0, names.size() - 1);
    for (std::size_t t = 0; t < n_tracks; ++t) {
        generated_track track{std::string(names[(first + t) % names.size()]), {}};
        // (times of a few minutes at most: resample's frames stay few)
        long long time = in.ConsumeIntegralInRange<long long>(0, 100);
        const int time_decimals = in.ConsumeIntegralInRange(1, 3);
        const std::size_t n_keys = in.ConsumeIntegralInRange<std::size_t>(1, 8);
        for (std::size_t k = 0; k < n_keys; ++k) {
            generated_key key;
            key.time = decimal(time, time_decimals);
            time += in.ConsumeIntegralInRange<long long>(1, 300);
            std::array<double, 4> q{};
            for (double& c : q) c = in.ConsumeIntegralInRange(-1000, 1000);
            if (q == std::array<double, 4>{}) q[0] = 1;
            const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
            for (std::size_t i = 0; i < 4; ++i) key.quat[i] = shortest(q[i] / n);
            for (number& c : key.translation) c = decimal(in.ConsumeIntegralInRange(-100000, 100000), 3);
            track.keys.push_back(std::move(key));
        }
        g.tracks.push_back(std::move(track));
    }
    return g;
}

std::string json_string(std::string_view s) { return fmt::format("\"{}\"", s); }  // (the names need no escapes)

std::string csv_text(const generated& g) {
    std::string out = g.translations ? "track,time,qw,qx,qy,qz,tx,ty,tz\n" : "track,time,qw,qx,qy,qz\n";
    for (const auto& t : g.tracks)
        for (const auto& k : t.keys) {
            out += fmt::format("{},{},{},{},{},{}", t.name, k.time.text, k.quat[0].text, k.quat[1].text, k.quat[2].text,
                               k.quat[3].text);
            if (g.translations)
                out += fmt::format(",{},{},{}", k.translation[0].text, k.translation[1].text, k.translation[2].text);
            out += '\n';
        }
    return out;
}

/// A key as JSON members: the quaternion as an array, or (`records`) as
/// the CSV's columns.
std::string json_members(const generated& g, const generated_key& k, bool records) {
    std::string out = fmt::format("\"time\": {}", k.time.text);
    if (records)
        out += fmt::format(", \"qw\": {}, \"qx\": {}, \"qy\": {}, \"qz\": {}", k.quat[0].text, k.quat[1].text,
                           k.quat[2].text, k.quat[3].text);
    else
        out += fmt::format(", \"quat\": [{}, {}, {}, {}]", k.quat[0].text, k.quat[1].text, k.quat[2].text, k.quat[3].text);
    if (g.translations && records)
        out += fmt::format(", \"tx\": {}, \"ty\": {}, \"tz\": {}", k.translation[0].text, k.translation[1].text,
                           k.translation[2].text);
    else if (g.translations)
        out += fmt::format(", \"translation\": [{}, {}, {}]", k.translation[0].text, k.translation[1].text,
                           k.translation[2].text);
    return out;
}

std::string json_document(const generated& g) {
    std::string out = "{\"tracks\": {";
    for (std::size_t t = 0; t < g.tracks.size(); ++t) {
        out += fmt::format("{}{}: {{\"keys\": [", t ? ", " : "", json_string(g.tracks[t].name));
        for (std::size_t k = 0; k < g.tracks[t].keys.size(); ++k)
            out += fmt::format("{}{{{}}}", k ? ", " : "", json_members(g, g.tracks[t].keys[k], false));
        out += "]}";
    }
    return out + "}}\n";
}

/// One object a key, each with its track: NDJSON lines, or (`array`) a JSON array.
std::string json_lines(const generated& g, bool records, bool array) {
    std::string out = array ? "[" : "";
    for (const auto& t : g.tracks)
        for (const auto& k : t.keys) {
            if (array && out.size() > 1) out += ",\n";
            out += fmt::format("{{\"track\": {}, {}}}", json_string(t.name), json_members(g, k, records));
            if (!array) out += '\n';
        }
    return array ? out + "]\n" : out;
}

/// The tracks as a BVH take: a chain of joints, one per track, each with
/// its own order of rotation channels (the root with positions where the
/// tracks have translations), every track's keys as frames (as many as
/// the longest track; the others repeat their last). The angles are the
/// keys' quaternion components scaled to degrees, `rotations` their
/// rotations as keyrot's Euler conversion makes them.
std::string bvh_text(const generated& g, FuzzedDataProvider& in, std::vector<std::vector<quat>>& rotations) {
    static constexpr std::array<std::string_view, 6> orders = {"XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX"};
    std::string out = "HIERARCHY\n";
    std::vector<std::string_view> order;
    std::size_t frames = 0;
    for (std::size_t t = 0; t < g.tracks.size(); ++t) {
        order.push_back(orders[in.ConsumeIntegralInRange<std::size_t>(0, orders.size() - 1)]);
        const std::string pad(t, '\t');
        out += fmt::format("{}{} {}\n{}{{\n{}\tOFFSET 0 {} 0\n{}\tCHANNELS {}", pad, t ? "JOINT" : "ROOT",
                           g.tracks[t].name, pad, pad, t, pad, t == 0 && g.translations ? 6 : 3);
        if (t == 0 && g.translations) out += " Xposition Yposition Zposition";
        for (char axis : order.back()) out += fmt::format(" {}rotation", axis);
        out += '\n';
        frames = std::max(frames, g.tracks[t].keys.size());
    }
    for (std::size_t t = g.tracks.size(); t-- > 0;) out += fmt::format("{}}}\n", std::string(t, '\t'));
    out += fmt::format("MOTION\nFrames: {}\nFrame Time: 0.0333333\n", frames);
    rotations.assign(g.tracks.size(), {});
    for (std::size_t f = 0; f < frames; ++f) {
        std::string line;
        for (std::size_t t = 0; t < g.tracks.size(); ++t) {
            const generated_key& k = g.tracks[t].keys[std::min(f, g.tracks[t].keys.size() - 1)];
            if (t == 0 && g.translations)
                line += fmt::format("{} {} {} ", k.translation[0].text, k.translation[1].text, k.translation[2].text);
            std::array<double, 3> angles{};
            for (std::size_t i = 0; i < 3; ++i) {
                const number a = shortest(k.quat[i + 1].value * 180);
                line += a.text + ' ';
                angles[i] = a.value;
            }
            rotations[t].push_back(from_euler(angles, *parse_euler_seq(order[t]), angle_unit::degrees));
        }
        line.back() = '\n';
        out += line;
    }
    return out;
}

/// How near two readings must be: exactly, or within a float's precision.
struct tolerance {
    double time = 0;      ///< relative
    double rotation = 0;  ///< the distance between unit quaternions (q and -q alike)
    double translation = 0;
};

/// How far apart two unit quaternions are, q and -q alike: the smaller
/// length of their difference and of their sum.
double apart(const quat& a, const quat& b) {
    const double dw = a.w - b.w, dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
    const double sw = a.w + b.w, sx = a.x + b.x, sy = a.y + b.y, sz = a.z + b.z;
    return std::sqrt(std::min(dw * dw + dx * dx + dy * dy + dz * dz, sw * sw + sx * sx + sy * sy + sz * sz));
}

[[noreturn]] void differ(std::string_view what, const std::string& detail) {
    std::fprintf(stderr, "fuzz_formats: %.*s: %s\n", static_cast<int>(what.size()), what.data(), detail.c_str());
    std::abort();
}

void require_same(std::string_view what, const document& a, const document& b, const tolerance& tol) {
    if (a.tracks.size() != b.tracks.size())
        differ(what, fmt::format("{} tracks, then {}", a.tracks.size(), b.tracks.size()));
    for (std::size_t t = 0; t < a.tracks.size(); ++t) {
        const track &x = a.tracks[t], &y = b.tracks[t];
        if (x.name != y.name || x.keys.size() != y.keys.size())
            differ(what, fmt::format("track '{}' of {} keys, then '{}' of {}", x.name, x.keys.size(), y.name, y.keys.size()));
        for (std::size_t i = 0; i < x.keys.size(); ++i) {
            const key &p = x.keys[i], &q = y.keys[i];
            const double distance = apart(p.rotation, q.rotation);
            if (std::fabs(p.time - q.time) > tol.time * std::max(1.0, std::fabs(p.time)) || distance > tol.rotation)
                differ(what, fmt::format("'{}' key {}: time {} and {}, quaternions {} apart", x.name, i, p.time, q.time,
                                         distance));
            // No translation means none: a 4x4 matrix writes it as zeros.
            const vec3 e = p.translation.value_or(vec3{0, 0, 0}) - q.translation.value_or(vec3{0, 0, 0});
            if (std::max({std::fabs(e.x), std::fabs(e.y), std::fabs(e.z)}) >
                tol.translation * std::max(1.0, norm(p.translation.value_or(vec3{0, 0, 0}))))
                differ(what, fmt::format("'{}' key {}: translations {} apart", x.name, i, norm(e)));
        }
    }
}

/// `text` read as `f` (Euler angles in `euler`, which CSV and NDJSON do
/// not state); a finding where that fails, as it must not.
document read(std::string_view text, format f, const std::optional<euler_seq>& euler = std::nullopt) {
    read_options ro;
    ro.source = "fuzz";
    ro.settings.euler = euler;
    std::ostringstream said;
    warnings warn(said, "fuzz");
    std::istringstream in{std::string(text)};
    try {
        return read_document(in, f, ro, warn);
    } catch (const error& e) {
        differ(fmt::format("reading format {}", static_cast<int>(f)),
               fmt::format("{}\n{}", e.what(), text.substr(0, 2000)));
    }
}

/// What the command writes of `input`, flags that make a command line: a
/// finding where it fails, as it must not on valid tracks.
std::string valid_command(std::string_view what, const options& o, std::string_view input) {
    const auto r = fuzz::run_command(o, input);
    if (!r.status) differ(what, "not a command line: " + r.refused);
    if (*r.status != 0) differ(what, r.err);
    return r.out;
}

constexpr tolerance exact{}, single_precision{1e-6, 1e-6, 1e-6};
// Text that reads back the same double, through conversions between
// representations (an Euler sequence's, a matrix's).
constexpr tolerance converted{0, 1e-9, 0};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    FuzzedDataProvider in(data, size);
    const generated g = generate(in);

    // Every text reader reads the same keys to the bit.
    const std::string csv = csv_text(g);
    const document keys = read(csv, format::csv);
    require_same("JSON document", keys, read(json_document(g), format::json), exact);
    require_same("NDJSON", keys, read(json_lines(g, false, false), format::ndjson), exact);
    require_same("NDJSON records", keys, read(json_lines(g, true, false), format::ndjson), exact);
    require_same("JSON records", keys, read(json_lines(g, true, true), format::json), exact);

    // BVH: each joint's rotations those of its Euler angles.
    std::vector<std::vector<quat>> rotations;
    const std::string bvh = bvh_text(g, in, rotations);
    const document take = read(bvh, format::bvh);
    for (std::size_t t = 0; t < take.tracks.size(); ++t)
        for (std::size_t f = 0; f < take.tracks[t].keys.size(); ++f) {
            if (apart(take.tracks[t].keys[f].rotation, rotations[t][f]) > 1e-12)
                differ("BVH", fmt::format("joint {} frame {}", t, f));
        }

    // glTF, as keyrot writes it.
    for (const format f : {format::glb, format::gltf}) {
        options o;
        o.cmd = command::convert;
        o.from = format::csv;
        o.to = f;
        require_same("glTF", keys, read(valid_command("to glTF", o, csv), f), single_precision);
    }

    // A command's output in another format and representation means what
    // its CSV of quaternions means.
    options o;
    static constexpr std::array<command, 3> commands = {command::convert, command::resample, command::reduce};
    o.cmd = commands[in.ConsumeIntegralInRange<std::size_t>(0, commands.size() - 1)];
    o.from = in.ConsumeBool() ? format::csv : format::bvh;
    o.how = std::array{method::slerp, method::nlerp, method::squad, method::step,
                       method::cubic}[in.ConsumeIntegralInRange<std::size_t>(0, 4)];
    // (reduce refuses the spline; a track of one key has none)
    const bool lone_key = std::any_of(g.tracks.begin(), g.tracks.end(), [](const auto& t) { return t.keys.size() == 1; });
    if (o.how == method::cubic && (o.cmd == command::reduce || lone_key)) o.how = method::slerp;
    o.fps = std::array{24.0, 30.0, 7.5}[in.ConsumeIntegralInRange<std::size_t>(0, 2)];
    o.tol_deg = in.ConsumeBool() ? 0.5 : 0;
    o.max_frames = 1e5;
    const std::string_view input = o.from == format::csv ? std::string_view(csv) : std::string_view(bvh);
    options plain = o;
    plain.to = format::csv;
    plain.representation = rep::quat;
    const std::string reference = valid_command("the command to CSV", plain, input);
    // A lone key off the frame grid gives no frame: an empty table, which
    // reads as no keys (an error), and nothing to compare.
    if (std::count(reference.begin(), reference.end(), '\n') < 2) return 0;
    static constexpr std::array outputs = {format::csv, format::json, format::ndjson, format::glb, format::bvh};
    const format to = outputs[in.ConsumeIntegralInRange<std::size_t>(0, outputs.size() - 1)];
    o.to = to == format::bvh && o.from != format::bvh ? format::gltf : to;
    o.representation = std::array{rep::quat, rep::axis_angle, rep::rotvec, rep::euler, rep::matrix,
                                  rep::matrix4}[in.ConsumeIntegralInRange<std::size_t>(0, 5)];
    if (o.representation == rep::euler) o.out_euler = parse_euler_seq(in.ConsumeBool() ? "ZYX" : "xyz");
    o.order = in.ConsumeBool() ? quat_order::xyzw : quat_order::wxyz;
    if (in.ConsumeBool()) o.out_angles = angle_unit::radians;
    const std::string what = fmt::format("command {} to format {} as rep {}", static_cast<int>(o.cmd),
                                         static_cast<int>(*o.to), static_cast<int>(o.representation));
    const bool binary = *o.to == format::glb || *o.to == format::gltf;
    const auto output = fuzz::run_command(o, input);
    if (!output.status) return 0;  // (flags that make no command line: squad into glTF)
    if (*output.status != 0) differ(what, output.err);
    require_same(what, read(reference, format::csv), read(output.out, *o.to, o.out_euler),
                 binary ? single_precision : converted);
    return 0;
}
