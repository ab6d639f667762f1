// SPDX-License-Identifier: MIT
#pragma once
// Shared test helpers. doctest::Approx defaults to ~1e-5, far too loose for
// rotations, so every comparison here names its tolerance.
#include <doctest/doctest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "keyrot/quat.hpp"
#include "keyrot/track.hpp"

namespace keyrot::test {

/// A key at `time` of rotation `q` (and frame number `frame`, if any), as a reader would make it.
inline key key_at(double time, quat q, std::optional<double> frame = std::nullopt) {
    key k;
    k.time = time;
    k.frame = frame;
    k.rotation = q;
    return k;
}

/// A fresh directory under the system's temporary directory, removed after.
struct scratch {
    std::filesystem::path dir;
    scratch() {
        dir = std::filesystem::temp_directory_path() / ("keyrot-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter()++));
        std::filesystem::remove_all(dir);
        std::filesystem::create_directories(dir);
    }
    ~scratch() { std::filesystem::remove_all(dir); }
    static int& counter() {
        static int n = 0;
        return n;
    }
    std::string file(const std::string& name, const std::string& text) const {
        std::ofstream(dir / name) << text;
        return (dir / name).string();
    }
    static std::string read(const std::filesystem::path& p) {
        std::ifstream in(p);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }
};

inline double max_diff(quat a, quat b) {
    return std::fmax(std::fmax(std::fabs(a.w - b.w), std::fabs(a.x - b.x)),
                     std::fmax(std::fabs(a.y - b.y), std::fabs(a.z - b.z)));
}

/// Same rotation (q or -q) to within tol per component.
inline bool same_rotation(quat a, quat b, double tol) {
    return max_diff(a, b) <= tol || max_diff(a, -b) <= tol;
}

inline bool near(double a, double b, double tol) { return std::fabs(a - b) <= tol; }

/// Uniformly random unit quaternions, reproducible.
class random_rotations {
public:
    explicit random_rotations(unsigned seed) : gen_(seed) {}
    quat next() {
        std::normal_distribution<double> n;
        quat q{n(gen_), n(gen_), n(gen_), n(gen_)};
        const double len = norm(q);
        return {q.w / len, q.x / len, q.y / len, q.z / len};
    }
    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(gen_); }

private:
    std::mt19937_64 gen_;
};

}  // namespace keyrot::test
