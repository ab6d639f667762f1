// keyrot's benchmark (run by hand, not by the tests): generates quaternion
// tracks, runs `keyrot resample track.csv -o out.csv --rep axis-angle` and,
// where python3 has numpy and scipy, the script a scipy user would write
// (loadtxt -> Slerp -> as_rotvec -> savetxt), several times each, and
// prints median wall time, frames per second, peak RSS and the ratio.
//
// Usage: keyrot_bench [--runs N] [--keyrot PATH] [--python PATH] [--dir DIR]
#include <fmt/format.h>
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
    double seconds;
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
    const auto start = std::chrono::steady_clock::now();
    pid_t pid;
    if (posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ) != 0) return {0, 0, -1};
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    posix_spawn_file_actions_destroy(&actions);
    return {seconds, usage.ru_maxrss, WIFEXITED(status) ? WEXITSTATUS(status) : -1};
}

struct summary {
    double median_s;
    long peak_kb;
    bool ok;
};

summary repeat(const std::vector<std::string>& argv, int runs) {
    std::vector<double> times;
    long peak = 0;
    bool ok = true;
    for (int i = 0; i < runs; ++i) {
        const measurement m = run(argv);
        times.push_back(m.seconds);
        peak = std::max(peak, m.peak_kb);
        ok = ok && m.status == 0;
    }
    std::sort(times.begin(), times.end());
    return {times[times.size() / 2], peak, ok};
}

/// A track of `keys` random unit quaternions, 5 frames apart at 24 fps.
std::size_t write_track(const std::string& path, std::size_t keys) {
    std::mt19937_64 gen(7);
    std::normal_distribution<double> n;
    // Line by line: Linux counts the spawning process's own peak into the
    // child's ru_maxrss, so the benchmark keeps its memory small.
    std::ofstream out(path);
    out << "time,qw,qx,qy,qz\n";
    for (std::size_t i = 0; i < keys; ++i) {
        double q[4] = {n(gen), n(gen), n(gen), n(gen)};
        const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        out << fmt::format("{},{},{},{},{}\n", static_cast<double>(i) * 5 / 24, q[0] / len, q[1] / len, q[2] / len,
                           q[3] / len);
    }
    return (keys - 1) * 5 + 1;  // frames
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

}  // namespace

int main(int argc, char** argv) {
    int runs = 5;
    std::string keyrot = KEYROT_BINARY, python, dir = (std::filesystem::temp_directory_path() / "keyrot-bench").string();
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string flag = argv[i];
        if (flag == "--runs") runs = std::max(1, std::atoi(argv[i + 1]));
        else if (flag == "--keyrot") keyrot = argv[i + 1];
        else if (flag == "--python") python = argv[i + 1];
        else if (flag == "--dir") dir = argv[i + 1];
    }
    std::filesystem::create_directories(dir);
    python = find_python(python);
    const std::string script = dir + "/slerp_scipy.py";
    std::ofstream(script) << scipy_script;

    fmt::print("keyrot benchmark: {} cores, {}, median of {} runs\n", std::thread::hardware_concurrency(), cpu_model(),
               runs);
    fmt::print("{:<34} {:>10} {:>12} {:>10}\n", "", "median s", "frames/s", "peak RSS");
    for (const std::size_t keys : {std::size_t{200000}, std::size_t{800000}}) {
        const std::string track = fmt::format("{}/track{}.csv", dir, keys);
        const std::size_t frames = write_track(track, keys);
        const auto mine = repeat({keyrot, "resample", track, "-o", dir + "/out.csv", "--rep", "axis-angle"}, runs);
        fmt::print("{:<34} {:>10.3f} {:>10.2f} M {:>7.1f} MB{}\n",
                   fmt::format("keyrot, {:.1f}M frames", static_cast<double>(frames) / 1e6), mine.median_s,
                   static_cast<double>(frames) / mine.median_s / 1e6, static_cast<double>(mine.peak_kb) / 1024,
                   mine.ok ? "" : "  FAILED");
        fmt::print("{:<34} {:>10.3f}\n", "  per million frames", mine.median_s * 1e6 / static_cast<double>(frames));
        if (python.empty()) {
            fmt::print("  scipy: not run (no python3 with numpy and scipy; apt-get install python3-scipy)\n");
            continue;
        }
        if (keys > 200000) continue;  // the scipy script at 4M frames takes most of a minute a run
        const auto theirs = repeat({python, script, track, dir + "/out_scipy.csv"}, runs);
        fmt::print("{:<34} {:>10.3f} {:>10.2f} M {:>7.1f} MB{}\n", "scipy script", theirs.median_s,
                   static_cast<double>(frames) / theirs.median_s / 1e6, static_cast<double>(theirs.peak_kb) / 1024,
                   theirs.ok ? "" : "  FAILED");
        fmt::print("{:<34} {:>10.1f}x\n", "  ratio (scipy / keyrot)", theirs.median_s / mine.median_s);
    }
    const std::string small = dir + "/ten.csv";
    write_track(small, 10);
    const auto start = repeat({keyrot, "resample", small, "-o", dir + "/ten_out.csv"}, runs * 10);
    fmt::print("{:<34} {:>10.2f} ms\n", "keyrot start-up, 10 keys", start.median_s * 1e3);
}
