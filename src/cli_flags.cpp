// SPDX-License-Identifier: MIT
#include "cli_flags.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <numbers>

#include "app/usage_error.hpp"
#include "io/common/source.hpp"
#include "ground/text.hpp"

namespace keyrot::cli {

namespace {

/// An enumeration's names, for CLI::IsMember.
template <named_enum E>
std::vector<std::string> names() {
    std::vector<std::string> list;
    for (const auto& n : names_of<E>) list.emplace_back(n.name);
    return list;
}

/// Flags for reading keys (every command but slerp).
void add_input_flags(CLI::App& sub, options& o, raw_flags& f) {
    sub.option_defaults()->group("Input");
    sub.add_option("--from", f.from, "input format (default: by extension, else sniffed)")
        ->check(CLI::IsMember(names<format>()));
    sub.add_flag("--strict", o.strict, "a quaternion whose norm is not 1 is an error");
    sub.add_option("--key-fps", f.key_fps,
                   fmt::format("frame rate of 'frame' keys (default: the file's, else 24{})",
                               sub.get_name() == "resample" ? ", whatever --fps is" : ""));
    sub.add_option("--max-bytes", o.max_bytes,
                   fmt::format("most bytes a CSV, NDJSON or BVH line (default {} MiB), or a JSON document or a glTF "
                               "file read whole (default {} MiB), may take",
                               default_max_line_bytes >> 20, default_max_bytes >> 20));
    sub.add_option("--animation", o.animation, "glTF: the one animation to read, by name or index (default: all)");
}

/// The angle and quaternion conventions of the input (and of the output,
/// for the commands that write rotations).
void add_convention_flags(CLI::App& sub, options& o, raw_flags& f) {
    sub.option_defaults()->group("Conventions");
    sub.add_option("--euler", f.euler, "Euler sequence of the input, e.g. ZYX (intrinsic) or xyz (extrinsic)");
    sub.add_option("--quat-order", f.quat_order,
                   fmt::format("order of quaternion arrays and output columns (default: {})", to_string(quat_order::wxyz)))
        ->check(CLI::IsMember(names<quat_order>()));
    sub.add_flag("--radians", o.radians, "angles in radians, input and output (default: degrees)");
}

void add_fsync_flag(CLI::App& sub, options& o) {
    sub.add_flag("--fsync", o.fsync,
                 "output files durable against a power cut, not only replaced whole (waits for the disk)");
}

/// Flags for writing rotations, and the conventions.
void add_output_flags(CLI::App& sub, options& o, raw_flags& f) {
    sub.option_defaults()->group("Output");
    sub.add_option("-o,--output", o.output, "output file (default: standard output)");
    add_fsync_flag(sub, o);
    sub.add_option("--to", f.to, "output format (default: extension of -o, else the input format)")
        ->check(CLI::IsMember(names<format>()));
    sub.add_option("--rep", f.rep, "output representation (default: axis-angle; reduce: quat)")
        ->check(CLI::IsMember(names<rep>()));
    sub.add_option("--out-euler", f.out_euler, "Euler sequence of the output (default: --euler)");
    auto* deg = sub.add_flag("--out-degrees", f.out_degrees, "output angles in degrees");
    auto* rad = sub.add_flag("--out-radians", f.out_radians, "output angles in radians");
    deg->excludes(rad);
    sub.add_option("--precision", f.precision, "digits after the decimal point (default: shortest round trip)");
    sub.add_flag("--compact", o.compact,
                 "glTF output: rotations as normalised 16-bit integers, half the bytes, each within 0.0035 deg of "
                 "exact (default: 32-bit floats)");
    sub.add_flag("--euler-continuous", o.euler_continuous,
                 "Euler output continuous from frame to frame, not in canonical ranges (always for BVH; the keys "
                 "of Euler input in the output's sequence keep their own angles)");
    sub.add_option("--settings-line", f.settings_line,
                   fmt::format("CSV, NDJSON: a first line of the settings the output was written with, always "
                               "or never (default: {}; the columns' names say what keyrot needs to read it back)",
                               to_string(settings_line::never)))
        ->check(CLI::IsMember(names<settings_line>()));
    add_convention_flags(sub, o, f);
}

void add_method_flags(CLI::App& sub, raw_flags& f) {
    sub.option_defaults()->group("Interpolation");
    // cubicspline is not offered: it needs the tangents only a glTF file's keys have.
    std::vector<std::string> methods = names<method>();
    std::erase(methods, to_string(method::cubicspline));
    sub.add_option("--method", f.method,
                   fmt::format("interpolation method (default: {}, or a glTF sampler's own)", to_string(method::slerp)))
        ->check(CLI::IsMember(methods));
    sub.add_option("--path", f.path,
                   fmt::format("shortest: consecutive keys in one hemisphere; direct: signs as given (default: {})",
                               f.path))
        ->check(CLI::IsMember(names<path>()));
}

euler_seq euler_flag(const std::string& flag, const std::string& value) {
    if (auto seq = parse_euler_seq(value)) return *seq;
    throw usage_error(fmt::format("{}: expected three axes like ZYX (intrinsic) or xyz (extrinsic), no two "
                                  "consecutive ones equal, got '{}'",
                                  flag, excerpt(value)));
}

/// An angle flag's value in degrees: a number, or a number and its unit,
/// "deg", "°" or "rad" ("0.1deg", "0.002 rad").
double angle_flag(const char* flag, std::string_view text) {
    std::string_view number = trim(text);
    double per_unit = 1;
    for (const auto& [unit, degrees] : {std::pair("deg", 1.0), std::pair("°", 1.0), std::pair("rad", 180 / std::numbers::pi)})
        if (number.ends_with(unit)) {
            number = trim(number.substr(0, number.size() - std::string_view(unit).size()));
            per_unit = degrees;
            break;
        }
    const auto v = parse_number(number);
    if (!v) throw usage_error(fmt::format("{}: expected an angle in degrees, like 0.1 or 0.1deg (or 0.002rad), got '{}'", flag, excerpt(text)));
    return *v * per_unit;
}

void check_rate(const char* flag, double v) {
    // A subnormal rate has no finite frame period: 1e-320 fps is no rate.
    if (!(std::isnormal(v) && v > 0)) throw usage_error(fmt::format("{}: expected a positive frame rate, got {}", flag, v));
}


void add_batch_flags(CLI::App& sub, options& o, raw_flags& f) {
    sub.add_option("files", o.inputs, "input files ('-' or none: standard input)");
    sub.option_defaults()->group("Files");
    sub.add_option("--output-dir", o.output_dir, "directory for the outputs of several inputs");
    sub.add_option("--jobs", f.jobs, "files converted at once (default: the number of cores)");
}

void define_resample(CLI::App& sub, options& o, raw_flags& f) {
    add_batch_flags(sub, o, f);
    add_input_flags(sub, o, f);
    add_output_flags(sub, o, f);
    add_method_flags(sub, f);
    sub.add_option("--fps", o.fps, fmt::format("output frame rate (default {})", o.fps));
    sub.add_option("--max-frames", o.max_frames,
                   fmt::format("most frames a track may make (default {:.0f}: {:.0f} hours at {} fps)", o.max_frames,
                               o.max_frames / o.fps / 3600, o.fps));
    sub.option_defaults()->group("Velocity");
    sub.add_flag("--velocity", o.velocity, "add each frame's angular velocity (wx wy wz, output angle unit per second)");
    sub.add_flag("--acceleration", o.acceleration, "add its angular acceleration (dwx dwy dwz, per second squared)");
    sub.add_option("--velocity-frame", f.velocity_frame,
                   "body: about the object's own axes, as a gyroscope reads; world: the fixed axes (default: body)")
        ->check(CLI::IsMember(names<motion_frame>()));
    sub.footer(R"(Examples:
  keyrot resample walk.csv --fps 30 -o walk30.json
  keyrot resample turntable.csv --method squad --rep quat --precision 6
  keyrot resample turntable.csv --method cubic --velocity --acceleration -o smooth.json
  keyrot resample *.csv --fps 60 --to ndjson --output-dir resampled)");
}

void define_convert(CLI::App& sub, options& o, raw_flags& f) {
    add_batch_flags(sub, o, f);
    add_input_flags(sub, o, f);
    add_output_flags(sub, o, f);
    sub.footer(R"(Examples:
  keyrot convert walk.csv --rep euler --euler ZYX -o walk.ndjson
  keyrot convert homework.json --rep matrix --to csv
  keyrot convert head_turn.json --rep rotvec --out-radians)");
}

void define_slerp(CLI::App& sub, options& o, raw_flags& f) {
    sub.add_option("Q0", o.q0, "first rotation, comma-separated (see --from-rep)")->required();
    sub.add_option("Q1", o.q1, "second rotation")->required();
    sub.option_defaults()->group("Interpolation");
    sub.add_option("-t", o.ts, "interpolation parameter in [0, 1]; may repeat, or be a list: -t 0.25,0.5,0.75")
        ->delimiter(',');
    sub.add_option("--steps", o.steps, "sample t = 0, 1/N, ..., 1");
    sub.add_option("--max-frames", o.max_frames, fmt::format("most rows --steps may make (default {:.0f})", o.max_frames));
    sub.add_option("--from-rep", f.from_rep,
                   fmt::format("what Q0 and Q1 are: quat (in --quat-order), axis-angle (ax,ay,az,angle), rotvec, "
                               "euler (needs --euler) (default: {})",
                               f.from_rep))
        ->check(CLI::IsMember({"quat", "axis-angle", "rotvec", "euler"}));
    add_method_flags(sub, f);
    add_output_flags(sub, o, f);
    sub.footer(R"(Examples:
  keyrot slerp 1,0,0,0 0.7071068,0,0,0.7071068 -t 0.5
  keyrot slerp 0,0,1,0 0,0,1,90 --from-rep axis-angle --steps 4 --rep quat
  keyrot slerp 0,0,0 90,0,0 --from-rep euler --euler ZYX --method nlerp -t 0.25 -t 0.75)");
}

void define_compare(CLI::App& sub, options& o, raw_flags& f) {
    sub.add_option("KEY", o.inputs,
                   "the key (expected rotations), then one answer or more to grade ('-': standard input)")
        ->required();
    sub.option_defaults()->group("Grading");
    sub.add_option("--tol", f.tol,
                   fmt::format("largest rotation difference, in degrees or with a unit: 0.1deg, 0.002rad (default {})",
                               o.tol_deg));
    sub.add_option("--tol-translation", o.tol_translation,
                   fmt::format("largest translation, scale or morph weight difference (default {})", o.tol_translation));
    sub.add_option("--tol-velocity", o.tol_velocity, "largest angular velocity difference, deg/s (default: not compared)");
    sub.add_option("--tol-acceleration", o.tol_acceleration,
                   "largest angular acceleration difference, deg/s^2 (default: not compared)");
    sub.add_flag("--ignore-extra", f.ignore_extra,
                 "grade only the rows the key has: rows and tracks only an answer has are counted, not failed");
    sub.option_defaults()->group("Output");
    sub.add_option("--report", f.report,
                   "csv or json on standard output: one answer's rows, or several answers' grade table (default: "
                   "the summary, or the grade table as text)")
        ->check(CLI::IsMember({"csv", "json"}));
    sub.add_option("-o,--output", o.output, "file for the summary, the report or the table (default: standard output)");
    sub.add_option("--plot", o.plot,
                   "also an SVG picture: each track's rotation difference over time, the tolerance, the failing rows");
    add_fsync_flag(sub, o);
    add_input_flags(sub, o, f);
    add_convention_flags(sub, o, f);
    sub.footer(R"(With one answer, a summary line (or --report's rows); with several, a grade table, one row per answer,
and a count on standard error.

Exit status: one answer: 0 every row within tolerance, 1 some row differs or is missing, 2 an error (the answer
unreadable among them); several: 0 every answer passes, 1 some answer fails or cannot be read, 2 a usage error or
an unreadable key.

Examples:
  keyrot convert walk.csv --rep matrix -o answer.csv && keyrot compare walk.csv answer.csv
  keyrot convert homework.json --rep euler --euler XYZ | keyrot compare homework.json - --report json)");
}

void define_reduce(CLI::App& sub, options& o, raw_flags& f) {
    add_batch_flags(sub, o, f);
    add_input_flags(sub, o, f);
    add_output_flags(sub, o, f);
    add_method_flags(sub, f);
    sub.option_defaults()->group("Tolerance");
    sub.add_option("--tol", f.tol,
                   fmt::format("largest rotation error at any input key, in degrees or with a unit: 0.1deg, 0.002rad "
                               "(default {})",
                               o.tol_deg));
    sub.add_option("--tol-translation", o.tol_translation,
                   fmt::format("largest translation, scale or morph weight error at any input key (default {})",
                               o.tol_translation));
    sub.add_option("--report", f.report,
                   "json: a JSON report per file on standard output, for keys written by -o or --output-dir")
        ->check(CLI::IsMember({"json"}));
    sub.add_option("--plot", o.plot,
                   "also an SVG picture: each track's rotation with the kept keys marked, and the replay's error");
    sub.footer(R"(Each track keeps its first key, its last, and the fewest between them such that the kept keys,
played with --method, are within --tol of every input key. A summary line per track goes to standard error.

Examples:
  keyrot reduce turntable.csv --tol 0.05 -o turntable_reduced.csv
  keyrot reduce arm_wave.gltf --tol 0.01 --tol-translation 0.0001 -o arm_wave_reduced.glb
  keyrot reduce walk.csv z_turn.json --output-dir reduced --report json
  keyrot reduce capture.bvh --tol 0.5 -o capture_reduced.json --plot kept.svg)");
}

void define_plot(CLI::App& sub, options& o, raw_flags& f) {
    sub.add_option("files", o.inputs, "input files ('-' or none: standard input)");
    sub.option_defaults()->group("Picture");
    sub.add_option("-o,--output", o.output, "the SVG file to write ('-': standard output)");
    add_fsync_flag(sub, o);
    sub.add_option("--rep", f.rep,
                   "what is drawn of a rotation: quat (its components), euler (its angles), angle (from the first "
                   "key) (default: euler where a sequence is known, else quat)")
        ->check(CLI::IsMember({"quat", "euler", "angle"}));
    sub.add_option("--out-euler", f.out_euler, "Euler sequence of the curves (default: --euler, else the file's)");
    sub.add_option("--track", o.track_patterns, "only the tracks so named, or matching a shell pattern ('arm*'); may repeat");
    sub.add_flag("--speed", o.speed, "a panel of each track's angular speed below its curves");
    add_method_flags(sub, f);
    add_input_flags(sub, o, f);
    add_convention_flags(sub, o, f);
    sub.footer(R"(A panel per track: its rotation over time as --method plays it between the keys, the keys
marked. Angles in degrees (--radians: radians).

Examples:
  keyrot plot walk.csv -o walk.svg
  keyrot plot turntable.csv --method squad --speed -o turntable.svg
  keyrot plot capture.bvh --track 'Left*' --rep angle -o left.svg)");
}

void define_info(CLI::App& sub, options& o, raw_flags& f) {
    sub.add_option("files", o.inputs, "input files ('-' or none: standard input)");
    sub.option_defaults()->group("Output");
    sub.add_option("-o,--output", o.output, "output file; a .json name writes JSON (default: standard output)");
    add_fsync_flag(sub, o);
    sub.add_option("--to", f.to, "json: a JSON description instead of text")->check(CLI::IsMember({"json"}));
    sub.add_option("--precision", f.precision, "digits after the decimal point in the text (default 6)");
    sub.add_flag("--segments", o.segments, "every segment's angle and speed, not only the largest (holds them all)");
    add_method_flags(sub, f);
    add_input_flags(sub, o, f);
    add_convention_flags(sub, o, f);
    sub.footer(R"(A summary of each track: its keys, span and spacing, its largest step between keys, and the keys
to look at (flipped, renormalised, near gimbal lock), and its speed: the largest angular speed and
acceleration of the curve --method plays (default: slerp, or a glTF sampler's own), and the segments
over ten times the median speed and over 360 deg/s, each also a warning (a flip, swapped joints or a
dropped marker in a captured take). --segments adds a line per segment.

Examples:
  keyrot info walk.csv
  keyrot info wide_turn.csv --segments
  keyrot info capture.bvh --method cubic
  keyrot info homework.json head_turn.json --to json)");
}

}  // namespace

const std::array<command_definition, 7> commands = {{
    {"resample", "resample keyframes on the frame grid", command::resample, define_resample},
    {"convert", "rewrite keys in another representation, no resampling", command::convert, define_convert},
    {"slerp", "interpolate between two rotations (worked examples, homework)", command::slerp, define_slerp},
    {"compare", "grade an answer: per-frame rotation difference", command::compare, define_compare},
    {"info", "describe a track: keys, span, largest step, warnings", command::info, define_info},
    {"reduce", "the fewest input keys that replay within a tolerance", command::reduce, define_reduce},
    {"plot", "draw the tracks' curves as an SVG picture", command::plot, define_plot},
}};

void finish(options& o, const raw_flags& f) {
    if (!f.from.empty()) o.from = parse<format>(f.from);
    if (!f.to.empty()) o.to = parse<format>(f.to);
    // reduce writes the keys it keeps as quaternions, the rotations as read.
    if (o.cmd == command::plot) {  // what is drawn (CLI11 took only these three)
        if (f.rep == "quat") o.curves = plot_curves::quat;
        if (f.rep == "euler") o.curves = plot_curves::euler;
        if (f.rep == "angle") o.curves = plot_curves::angle;
    } else {
        o.representation = !f.rep.empty() ? *parse<rep>(f.rep) : o.cmd == command::reduce ? rep::quat : rep::axis_angle;
    }
    if (o.plot && is_standard_stream(*o.plot))
        throw usage_error("--plot -: the picture needs a file of its own: expected a file name, like --plot diff.svg");
    if (!f.euler.empty()) o.euler = euler_flag("--euler", f.euler);
    if (!f.out_euler.empty()) o.out_euler = euler_flag("--out-euler", f.out_euler);
    if (!f.quat_order.empty()) o.order = *parse<quat_order>(f.quat_order), o.order_given = true;
    if (f.out_degrees) o.out_angles = angle_unit::degrees;
    if (f.out_radians) o.out_angles = angle_unit::radians;
    if (f.precision) {
        if (*f.precision < 0 || *f.precision > 17)
            throw usage_error(fmt::format("--precision: expected 0 to 17 digits, got {}", *f.precision));
        o.precision = f.precision;
    }
    o.from_rep = *parse<rep>(f.from_rep);
    if (!f.settings_line.empty()) o.settings_when = *parse<settings_line>(f.settings_line);
    if (!f.report.empty()) o.report = parse<format>(f.report);
    if (!f.tol.empty()) o.tol_deg = angle_flag("--tol", f.tol);
    if (o.cmd == command::compare && o.inputs.size() < 2)
        throw usage_error("compare: ANSWER is missing: expected the key, then one answer or more (see keyrot compare --help)");
    if (f.ignore_extra) o.extra = extra_rows::allowed;
    if (!f.method.empty()) o.how = parse<method>(f.method);
    o.way = *parse<path>(f.path);
    if (o.how == method::cubic && o.way == path::direct)
        throw usage_error("--method cubic turns the short way between keys, as scipy's RotationSpline does: "
                          "expected --path shortest");
    o.rates_frame = *parse<motion_frame>(f.velocity_frame);
    check_rate("--fps", o.fps);
    if (o.max_bytes && *o.max_bytes < 1) throw usage_error("--max-bytes: expected at least 1 byte, got 0");
    if (!(std::isfinite(o.max_frames) && o.max_frames >= 1))
        throw usage_error(fmt::format("--max-frames: expected a number of frames, at least 1, got {}", o.max_frames));
    if (f.jobs) {
        if (*f.jobs < 1 || *f.jobs > 1024) throw usage_error(fmt::format("--jobs: expected 1 to 1024, got {}", *f.jobs));
        o.jobs = static_cast<unsigned>(*f.jobs);
    }
    if (f.key_fps) {
        check_rate("--key-fps", *f.key_fps);
        o.key_fps = f.key_fps;
    }
    for (double t : o.ts)
        if (!std::isfinite(t)) throw usage_error(fmt::format("-t: expected a finite number, got {}", t));
    if (o.cmd == command::info && o.output && (o.output->ends_with(".csv") || o.output->ends_with(".ndjson")))
        throw usage_error(fmt::format("-o {}: info writes text, or JSON with --to json or a .json name", *o.output));
}

}  // namespace keyrot::cli
