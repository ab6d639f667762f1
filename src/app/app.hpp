// SPDX-License-Identifier: MIT
#pragma once
// The commands, run on an options struct with the streams passed in, so the
// whole program can be run in-process by the tests.
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "app/usage_error.hpp"
#include "io/common/format.hpp"
#include "io/common/layout.hpp"
#include "keyrot/compare.hpp"
#include "keyrot/convert.hpp"
#include "keyrot/interpolate.hpp"
#include "keyrot/resample.hpp"

namespace keyrot {

enum class command { resample, convert, slerp, compare, info, reduce, plot };

/// What plot draws of a rotation: its quaternion's components, its Euler
/// angles, or its angle from the track's first key.
enum class plot_curves { quat, euler, angle };

struct options {
    command cmd = command::resample;
    std::vector<std::string> inputs;  ///< "-" is standard input; empty means "-"
    std::optional<std::string> output;      ///< -o; standard output when absent or "-"
    std::optional<std::string> output_dir;  ///< --output-dir, for several inputs
    std::optional<format> from, to;
    rep representation = rep::axis_angle;
    std::optional<euler_seq> euler, out_euler;
    quat_order order = quat_order::wxyz;
    bool order_given = false;  ///< --quat-order was typed (a file stating another order then warns)
    bool radians = false;
    std::optional<angle_unit> out_angles;  ///< --out-degrees / --out-radians
    std::optional<int> precision;
    bool euler_continuous = false;  ///< --euler-continuous
    settings_line settings_when = settings_line::never;  ///< --settings-line
    bool strict = false;
    bool fsync = false;  ///< --fsync: outputs durable against a power cut
    bool compact = false;  ///< --compact: a glTF output's rotations as normalised 16-bit integers
    double fps = 24;
    std::optional<double> key_fps;  ///< none: the file's, else default_key_fps (not fps)
    std::optional<method> how;  ///< --method; by default a glTF sampler's own, else slerp
    path way = path::shortest;
    double max_frames = resample_options{}.max_frames;  ///< per track (--max-frames)
    bool velocity = false, acceleration = false;     ///< resample --velocity, --acceleration
    motion_frame rates_frame = motion_frame::body;   ///< --velocity-frame
    /// --max-bytes: a line, a JSON document or a glTF file read whole (none: default_max_line_bytes for
    /// a line, default_max_bytes for a document)
    std::optional<std::size_t> max_bytes;
    std::optional<std::string> animation;              ///< --animation: glTF, the one animation to read
    unsigned jobs = 0;          ///< --jobs: files converted at once; 0 = the number of cores
    bool progress = false;      ///< a progress line on err for several files (main: when stderr is a terminal)
    bool terminal_out = false;  ///< standard output is a terminal (main), where no binary output is written

    // slerp
    std::string q0, q1;            ///< comma-separated operands
    rep from_rep = rep::quat;      ///< what Q0 and Q1 are
    std::vector<double> ts;        ///< -t
    std::optional<int> steps;      ///< --steps N: t = 0, 1/N, ..., 1

    // compare, reduce
    double tol_deg = 0.01;
    double tol_translation = 0.001;
    std::optional<double> tol_velocity, tol_acceleration;  ///< compare --tol-velocity, --tol-acceleration
    std::optional<format> report;  ///< --report csv|json
    extra_rows extra = extra_rows::fail;  ///< compare --ignore-extra: allowed

    // info
    bool segments = false;  ///< --segments: every segment's angle and speed, not only the largest

    // plot, and compare's and reduce's pictures
    std::optional<std::string> plot;          ///< compare, reduce --plot FILE
    std::optional<plot_curves> curves;        ///< plot --rep (default: Euler angles where a sequence is known)
    std::vector<std::string> track_patterns;  ///< plot --track, shell patterns
    bool speed = false;                       ///< plot --speed
};

/// Runs one command. Data goes to `out` (unless -o / --output-dir), warnings
/// and errors to `err` as "keyrot: ..." lines. Returns the exit status:
/// 0 success, 1 compare found differences, 2 any error. Throws usage_error
/// for a bad combination of flags.
///
///     keyrot::options o;
///     o.cmd = keyrot::command::resample;
///     o.inputs = {"walk.csv"};
///     o.fps = 30;
///     const int status = keyrot::run(o, std::cin, std::cout, std::cerr);
int run(const options& opts, std::istream& in, std::ostream& out, std::ostream& err);

}  // namespace keyrot
