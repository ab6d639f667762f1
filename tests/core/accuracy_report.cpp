// SPDX-License-Identifier: MIT
// Prints the worst error of each conversion and interpolation per angle
// decade against the __float128 reference (the README's accuracy table).
// Usage: accuracy_report [SAMPLES]   (default 200 per band and measurement)
#include <fmt/format.h>

#include <cstdlib>

#include "accuracy.hpp"

int main(int argc, char** argv) {
    using namespace keyrot::accuracy;
    const int samples = argc > 1 ? std::atoi(argv[1]) : 200;
    const auto all = bands();
    // Decades far from the edges are grouped ten at a time to keep the table short.
    std::vector<std::pair<std::string, std::vector<band>>> rows;
    for (int e = -100; e < -10; e += 10)
        rows.push_back({fmt::format("1e{}..1e{}", e, e + 10), {all.begin() + (e + 100), all.begin() + (e + 110)}});
    for (std::size_t i = 90; i < all.size(); ++i) rows.push_back({all[i].label, {all[i]}});

    const auto ms = measurements();
    fmt::print("| angle |");
    for (const auto& m : ms) fmt::print(" {} ({}) |", m.name, m.unit);
    fmt::print("\n|---|");
    for (std::size_t i = 0; i < ms.size(); ++i) fmt::print("---|");
    fmt::print("\n");
    std::vector<double> overall(ms.size(), 0);
    for (const auto& [label, group] : rows) {
        fmt::print("| {} |", label);
        for (std::size_t i = 0; i < ms.size(); ++i) {
            double w = 0;
            for (const band& b : group) w = std::fmax(w, worst(ms[i], b, samples, 17));
            overall[i] = std::fmax(overall[i], w);
            fmt::print(" {:.2g} |", w);
        }
        fmt::print("\n");
    }
    fmt::print("| **worst** |");
    for (double w : overall) fmt::print(" **{:.2g}** |", w);
    fmt::print("\n| bound |");
    for (const auto& m : ms) fmt::print(" {:.2g} |", m.bound);
    fmt::print("\n");
}
