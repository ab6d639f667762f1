// SPDX-License-Identifier: MIT
// keyrot's benchmark (run by hand, not by the tests): generates quaternion
// tracks (numbers in shortest form, and in numpy's savetxt form; keys 5
// frames apart, and dense keys at 120 Hz as motion capture gives), runs
// `keyrot resample track.csv -o out.csv --rep axis-angle` and, where python3
// has numpy and scipy, the script a scipy user would write (loadtxt ->
// Slerp -> as_rotvec -> savetxt), several times each, taking turns, and
// prints median wall time, frames per second, peak RSS and the ratio. The
// first track's command is also timed writing a new file each run. With
// --baseline, another keyrot binary (say, before a change) runs the same
// commands in the same turns, and the ratio of the two is printed. Last,
// `compare` and `info` of 200,000 and 1,000,000 resampled rows, each against
// `resample` of the same rows; reduce of the 1,000,000 rows against convert
// of them; a JSON document read whole against the same keys streamed. First
// of all, the floor: the 1M-frame job against keyrot_floor (the same input
// parsed by keyrot's reader and as many numbers printed, with no math, on
// two threads: with std::to_chars, and with keyrot's number writer), the
// same job with squad and with matrix output (and the floor of matrix
// rows), and the scipy script, taking turns, and summary lines of the
// ratios and of the CPU times.
//
// Usage: keyrot_bench [--runs N] [--keyrot PATH] [--baseline PATH] [--python PATH] [--dir DIR] [--only floor|start-up|json|reduce]
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>
#include <string>
#include <vector>

extern char** environ;

namespace {

struct measurement {
    double seconds, cpu_seconds;  // wall; user and system
    long peak_kb;
    int status;
};

/// Runs argv (stdout and stderr to /dev/null), timing it and taking its peak RSS.
measurement run(const std::vector<std::string>& argv) {
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    ::sync();  // no earlier run's output still being written back during this one
    const auto start = std::chrono::steady_clock::now();
    pid_t pid;
    if (posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ) != 0) return {0, 0, 0, -1};
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    posix_spawn_file_actions_destroy(&actions);
    const auto in_seconds = [](timeval t) {
        return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_usec) / 1e6;
    };
    return {seconds, in_seconds(usage.ru_utime) + in_seconds(usage.ru_stime), usage.ru_maxrss,
            WIFEXITED(status) ? WEXITSTATUS(status) : -1};
}

struct summary {
    double median_s, median_cpu_s;
    long peak_kb;
    bool ok;
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

/// A command to time, and a file to remove (untimed) before each of its runs.
struct command {
    std::vector<std::string> argv;
    std::string removed_first = {};
};

/// Runs each command `runs` times, taking turns (a b a b ...) so that a
/// shared machine's slow moments fall on all of them alike.
std::vector<summary> repeat(const std::vector<command>& commands, int runs) {
    std::vector<std::vector<double>> times(commands.size()), cpu_times(commands.size());
    std::vector<summary> out(commands.size(), summary{0, 0, 0, true});
    for (int i = 0; i < runs; ++i) {
        for (std::size_t c = 0; c < commands.size(); ++c) {
            if (!commands[c].removed_first.empty()) std::filesystem::remove(commands[c].removed_first);
            const measurement m = run(commands[c].argv);
            times[c].push_back(m.seconds);
            cpu_times[c].push_back(m.cpu_seconds);
            out[c].peak_kb = std::max(out[c].peak_kb, m.peak_kb);
            out[c].ok = out[c].ok && m.status == 0;
        }
    }
    for (std::size_t c = 0; c < commands.size(); ++c) {
        out[c].median_s = median(times[c]);
        out[c].median_cpu_s = median(cpu_times[c]);
    }
    return out;
}

/// How a track's numbers are written: shortest round-trip ("{}"), or as
/// numpy's savetxt writes them by default ("%.18e", 19 digits).
enum class digits { shortest, numpy };

/// A track of `keys` random unit quaternions, `density` keys every 5 frames
/// at 24 fps (25: 120 a second); returns its frames.
std::size_t write_track(const std::string& path, std::size_t keys, digits style = digits::shortest,
                        std::size_t density = 1) {
    std::mt19937_64 gen(7);
    std::normal_distribution<double> n;
    // Line by line: Linux counts the spawning process's own peak into the
    // child's ru_maxrss, so the benchmark keeps its memory small.
    std::ofstream out(path);
    out << "time,qw,qx,qy,qz\n";
    for (std::size_t i = 0; i < keys; ++i) {
        double q[4] = {n(gen), n(gen), n(gen), n(gen)};
        const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        const double time = static_cast<double>(i * 5) / static_cast<double>(24 * density);
        const double row[5] = {time, q[0] / len, q[1] / len, q[2] / len, q[3] / len};
        out << (style == digits::shortest ? fmt::format("{}\n", fmt::join(row, ","))
                                          : fmt::format("{:.18e}\n", fmt::join(row, ",")));
    }
    return (keys - 1) * 5 / density + 1;
}

constexpr const char* scipy_script = R"(import sys
import numpy as np
from scipy.spatial.transform import Rotation, Slerp
d = np.loadtxt(sys.argv[1], delimiter=",", skiprows=1)
t = d[:, 0]
slerp = Slerp(t, Rotation.from_quat(d[:, [2, 3, 4, 1]]))
k = np.arange(np.ceil(t[0] * 24), np.floor(t[-1] * 24) + 1)
rv = slerp(k / 24).as_rotvec()
np.savetxt(sys.argv[2], np.column_stack([k, k / 24, rv]), delimiter=",", header="frame,time,rx,ry,rz", comments="")
)";

std::string find_python(const std::string& given) {
    for (const std::string& candidate : {given, std::string("python3"), std::string("/usr/bin/python3")}) {
        if (candidate.empty()) continue;
        if (run({candidate, "-c", "import numpy, scipy"}).status == 0) return candidate;
    }
    return "";
}

std::string cpu_model() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown CPU";
}

void print_header() { fmt::print("{:<34} {:>10} {:>12} {:>10}\n", "", "median s", "frames/s", "peak RSS"); }

/// One row of the table: median time, frames (or keys) a second, peak RSS.
void print_row(const std::string& name, const summary& m, std::size_t frames) {
    fmt::print("{:<34} {:>10.3f} {:>10.2f} M {:>7.1f} MB{}\n", name, m.median_s,
               static_cast<double>(frames) / m.median_s / 1e6, static_cast<double>(m.peak_kb) / 1024,
               m.ok ? "" : "  FAILED");
}

/// A ratio under the rows it compares.
void print_ratio(const std::string& of, double ratio, int decimals = 2) {
    fmt::print("{:<34} {:>10.{}f}\n", "  ratio (" + of + ")", ratio, decimals);
}

/// The baseline's row, and keyrot's time (`m`) over the baseline's.
void print_baseline(const std::string& name, const summary& base, const summary& m, std::size_t count,
                    int decimals = 3) {
    print_row(name, base, count);
    print_ratio("keyrot / baseline", m.median_s / base.median_s, decimals);
}

/// A JSON document read whole (a setting after the keys it applies to, as
/// a script that writes "keys" first does: it is known only at the end)
/// against the same keys streamed: the whole read must stay linear in the
/// keys.
void json_read_whole(const std::string& keyrot, const std::string& baseline, const std::string& dir, int runs) {
    const std::string track = dir + "/json_track.csv", streamed = dir + "/streamed.json";
    const std::size_t keys = 100000;
    write_track(track, keys);
    run({keyrot, "convert", track, "-o", streamed, "--rep", "quat"});
    {
        // Line by line, as write_track: ...}]} at the end becomes ...}], "euler": "zyx"}.
        std::ifstream in(streamed);
        std::ofstream out(dir + "/whole.json");
        std::string line, next;
        std::getline(in, line);
        while (std::getline(in, next)) out << line << '\n', line = next;
        out << line.substr(0, line.rfind(']') + 1) << ", \"euler\": \"zyx\"}\n";
    }
    std::vector<command> commands = {{{keyrot, "convert", streamed, "-o", dir + "/json_out.csv"}},
                                     {{keyrot, "convert", dir + "/whole.json", "-o", dir + "/json_out.csv"}}};
    if (!baseline.empty()) commands.push_back({{baseline, "convert", dir + "/whole.json", "-o", dir + "/json_base.csv"}});
    const auto r = repeat(commands, runs);
    print_row("JSON of 0.1M keys, streamed", r[0], keys);
    print_row("the same read whole", r[1], keys);
    print_ratio("whole / streamed", r[1].median_s / r[0].median_s);
    if (!baseline.empty()) print_baseline("baseline, read whole", r[2], r[1], keys, 2);
}

/// reduce of the 1M rows resample writes (the floor's track, 200,000 keys,
/// resampled: keys on the arcs between the track's keys, which a reduce
/// finds again) against convert of the same rows, in the same turns (and
/// the baseline's reduce, if given).
void reduce_against_convert(const std::string& keyrot, const std::string& baseline, const std::string& dir, int runs) {
    const std::string track = dir + "/reduce_track.csv", rows = dir + "/reduce_rows.csv";
    const std::size_t count = write_track(track, 200000);  // the rows resample writes
    run({keyrot, "resample", track, "-o", rows});
    std::vector<command> commands = {{{keyrot, "reduce", rows, "--tol", "0.01", "-o", dir + "/reduced.csv"}},
                                     {{keyrot, "convert", rows, "-o", dir + "/converted.csv"}}};
    if (!baseline.empty())
        commands.push_back({{baseline, "reduce", rows, "--tol", "0.01", "-o", dir + "/reduced_baseline.csv"}});
    const auto r = repeat(commands, runs);
    print_row("reduce of 1M rows, --tol 0.01", r[0], count);
    print_row("convert of them (same turns)", r[1], count);
    print_ratio("reduce / convert", r[0].median_s / r[1].median_s);
    if (!baseline.empty()) print_baseline("baseline reduce", r[2], r[0], count);
}

/// A 10-key file, start to end, against a program that does nothing, in the
/// same turns (and against `baseline`, if given).
void start_up(const std::string& keyrot, const std::string& baseline, const std::string& dir, int runs) {
    const std::string small = dir + "/ten.csv";
    write_track(small, 10);
    std::vector<command> small_runs = {{{keyrot, "resample", small, "-o", dir + "/ten_out.csv"}}, {{"/bin/true"}}};
    if (!baseline.empty()) small_runs.push_back({{baseline, "resample", small, "-o", dir + "/ten_out_baseline.csv"}});
    const auto start = repeat(small_runs, runs * 10);
    fmt::print("{:<34} {:>10.2f} ms, {:.2f} ms more than /bin/true ({:.2f} ms)\n", "keyrot start-up, 10 keys",
               start[0].median_s * 1e3, (start[0].median_s - start[1].median_s) * 1e3, start[1].median_s * 1e3);
    if (!baseline.empty())
        fmt::print("{:<34} {:>10.2f} ms, ratio {:.3f}\n", "baseline start-up", start[2].median_s * 1e3,
                   start[0].median_s / start[2].median_s);
}

}  // namespace

int main(int argc, char** argv) {
    int runs = 5;
    std::string keyrot = KEYROT_BINARY, baseline, python, only,
                dir = (std::filesystem::temp_directory_path() / "keyrot-bench").string();
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string flag = argv[i];
        if (flag == "--runs") runs = std::max(1, std::atoi(argv[i + 1]));
        else if (flag == "--keyrot") keyrot = argv[i + 1];
        else if (flag == "--baseline") baseline = argv[i + 1];
        else if (flag == "--python") python = argv[i + 1];
        else if (flag == "--dir") dir = argv[i + 1];
        else if (flag == "--only") only = argv[i + 1];
    }
    std::filesystem::create_directories(dir);
    if (only == "start-up") {
        start_up(keyrot, baseline, dir, runs);
        return 0;
    }
    if (only == "json") {
        print_header();
        json_read_whole(keyrot, baseline, dir, runs);
        return 0;
    }
    if (only == "reduce") {
        print_header();
        reduce_against_convert(keyrot, baseline, dir, runs);
        return 0;
    }
    python = find_python(python);
    const std::string script = dir + "/slerp_scipy.py";
    std::ofstream(script) << scipy_script;

    fmt::print("keyrot benchmark: {} cores, {}, median of {} runs\n", std::thread::hardware_concurrency(), cpu_model(),
               runs);
    print_header();
    struct input {
        std::size_t keys;
        digits style = digits::shortest;
        std::size_t density = 1;
    };
    const auto print_per_million = [](const std::string& what, const summary& m, std::size_t count) {
        fmt::print("{:<34} {:>10.3f}\n", "  per million " + what, m.median_s * 1e6 / static_cast<double>(count));
    };
    {
        // The floor: keyrot against parsing and printing alone.
        const std::string track = dir + "/floor_track.csv";
        const std::size_t frames = write_track(track, 200000);
        const std::string rows = std::to_string(frames), columns = "6";  // frame,time,ax,ay,az,angle
        std::vector<command> commands = {
            {{keyrot, "resample", track, "-o", dir + "/out.csv", "--rep", "axis-angle"}},
            {{KEYROT_FLOOR, track, dir + "/floor_out.csv", rows, columns, "to_chars"}},
            {{KEYROT_FLOOR, track, dir + "/floor_keyrot_out.csv", rows, columns, "keyrot"}}};
        // The same job with squad, and with matrix output (9 numbers a row, not 4).
        commands.push_back({{keyrot, "resample", track, "-o", dir + "/out_squad.csv", "--rep", "axis-angle", "--method",
                             "squad"}});
        commands.push_back({{keyrot, "resample", track, "-o", dir + "/out_matrix.csv", "--rep", "matrix"}});
        // Matrix rows' own floor (frame, time and 9 numbers): the bytes it
        // writes are twice the main job's, and so is the printing.
        commands.push_back({{KEYROT_FLOOR, track, dir + "/floor_matrix_out.csv", rows, "11", "keyrot"}});
        if (!python.empty()) commands.push_back({{python, script, track, dir + "/out_scipy.csv"}});
        const auto r = repeat(commands, runs);
        print_row("keyrot, 1M frames", r[0], frames);
        print_row("floor, std::to_chars (same turns)", r[1], frames);
        print_row("floor, keyrot's writer", r[2], frames);
        print_row("keyrot --method squad", r[3], frames);
        print_row("keyrot --rep matrix", r[4], frames);
        print_row("floor, keyrot's writer, matrix rows", r[5], frames);
        if (!python.empty()) print_row("scipy script", r[6], frames);
        fmt::print("floor summary: keyrot / to_chars floor {:.2f}, keyrot / keyrot-writer floor {:.2f}{}; "
                   "squad / keyrot {:.2f}, matrix / keyrot {:.2f} (its floors: {:.2f} apart; "
                   "matrix / its keyrot-writer floor {:.2f})\n",
                   r[0].median_s / r[1].median_s, r[0].median_s / r[2].median_s,
                   python.empty() ? "" : fmt::format(", scipy / keyrot {:.1f}", r[6].median_s / r[0].median_s),
                   r[3].median_s / r[0].median_s, r[4].median_s / r[0].median_s, r[5].median_s / r[2].median_s,
                   r[4].median_s / r[5].median_s);
        // What the cores allow: no run takes less than its CPU time shared
        // out over every core.
        const double cores = std::max(1u, std::thread::hardware_concurrency());
        fmt::print("floor CPU time (user + system, median): keyrot {:.3f} s, squad {:.3f} s, matrix {:.3f} s; "
                   "over all {} cores, squad's is {:.2f} of keyrot's time, matrix's {:.2f}\n",
                   r[0].median_cpu_s, r[3].median_cpu_s, r[4].median_cpu_s, cores,
                   r[3].median_cpu_s / cores / r[0].median_s, r[4].median_cpu_s / cores / r[0].median_s);
    }
    if (only == "floor") return 0;
    const input inputs[] = {{200000}, {200000, digits::numpy}, {800000}, {1000000, digits::shortest, 25}};
    for (const input& in : inputs) {
        const bool numpy = in.style == digits::numpy, dense = in.density > 1;
        const std::string track =
            fmt::format("{}/track{}{}{}.csv", dir, in.keys, numpy ? "_numpy" : "", dense ? "_120hz" : "");
        const std::size_t frames = write_track(track, in.keys, in.style, in.density);
        std::vector<command> commands = {{{keyrot, "resample", track, "-o", dir + "/out.csv", "--rep", "axis-angle"}}};
        // The scipy script at 4M frames would take most of a minute a run.
        const bool with_scipy = !python.empty() && frames <= 1000000;
        if (with_scipy) commands.push_back({{python, script, track, dir + "/out_scipy.csv"}});
        // Each run above replaces the output of the run before, as the
        // script's does; freeing the old file's blocks can take the
        // filesystem a tenth of keyrot's run (docs/performance.md).
        const bool also_new_file = &in == &inputs[0];
        const std::string new_out = dir + "/new_out.csv";
        if (also_new_file)
            commands.push_back({{keyrot, "resample", track, "-o", new_out, "--rep", "axis-angle"}, new_out});
        if (!baseline.empty())
            commands.push_back({{baseline, "resample", track, "-o", dir + "/out_baseline.csv", "--rep", "axis-angle"}});
        const auto results = repeat(commands, runs);
        print_row(fmt::format("keyrot, {:.1f}M frames{}{}", static_cast<double>(frames) / 1e6, numpy ? ", %.18e" : "",
                              dense ? fmt::format(", {:.0f}M keys", static_cast<double>(in.keys) / 1e6) : ""),
                  results[0], frames);
        // Reading bounds a dense track's run, so its time goes with its keys.
        if (dense) print_per_million("keys", results[0], in.keys);
        else print_per_million("frames", results[0], frames);
        if (also_new_file) {
            print_row("keyrot, the same to a new file", results[commands.size() - 1 - !baseline.empty()], frames);
            print_per_million("frames", results[commands.size() - 1 - !baseline.empty()], frames);
        }
        if (!baseline.empty()) print_baseline("baseline (same turns)", results.back(), results[0], frames);
        if (python.empty()) {
            fmt::print("  scipy: not run (no python3 with numpy and scipy; apt-get install python3-scipy)\n");
        } else if (with_scipy) {
            print_row("scipy script (same turns)", results[1], frames);
            fmt::print("{:<34} {:>10.1f}x\n", "  ratio (scipy / keyrot)", results[1].median_s / results[0].median_s);
        }
    }
    // compare and info of the rows resample writes, each against resample
    // of the same rows, in the same turns.
    for (const std::size_t keys : {std::size_t{40000}, std::size_t{200000}}) {
        const std::string track = fmt::format("{}/rows_track{}.csv", dir, keys);
        const std::size_t frames = write_track(track, keys);
        const std::string rows = dir + "/rows.csv", other = dir + "/rows_nlerp.csv";
        run({keyrot, "resample", track, "-o", rows});
        run({keyrot, "resample", track, "--method", "nlerp", "-o", other});
        const auto r = repeat({{{keyrot, "resample", rows, "-o", dir + "/rows_out.csv"}},
                               {{keyrot, "compare", rows, other, "--tol", "180"}},
                               {{keyrot, "info", rows}}},
                              runs);
        print_row(fmt::format("resample of {:.1f}M rows", static_cast<double>(frames) / 1e6), r[0], frames);
        print_row("compare of them and another", r[1], frames);
        print_ratio("compare / resample", r[1].median_s / r[0].median_s);
        print_row("info of them", r[2], frames);
        print_ratio("info / resample", r[2].median_s / r[0].median_s);
    }
    reduce_against_convert(keyrot, baseline, dir, runs);
    json_read_whole(keyrot, baseline, dir, runs);
    start_up(keyrot, baseline, dir, runs);
}
