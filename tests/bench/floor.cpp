// SPDX-License-Identifier: MIT
// The floor under keyrot's main job (run by keyrot_bench, or by hand):
// what `keyrot resample track.csv -o out.csv` would cost with no math at
// all. One thread parses every number of the input with keyrot's own CSV
// reader; the other prints as many shortest round-trip doubles as keyrot's
// output holds (FRAMES rows of COLUMNS numbers: the frame, its time, then
// rotation-like numbers from a table made before the clock matters), with
// std::to_chars or with keyrot's number writer, into OUTPUT (an earlier
// OUTPUT removed as keyrot removes a file it replaces).
//
// Usage: keyrot_floor INPUT.csv OUTPUT FRAMES COLUMNS [to_chars|keyrot]
#include <sys/stat.h>

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "ground/warnings.hpp"
#include "keyrot/error.hpp"
#include "io/common/file_release.hpp"
#include "io/common/number_writer.hpp"
#include "io/open.hpp"

namespace {

/// Every key of `path` read by keyrot's CSV reader (its numbers parsed, no
/// quaternion made of them); returns how many.
std::size_t parse_all(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    keyrot::warnings warn(std::cerr, path);
    keyrot::read_options ro;
    ro.source = path;
    const auto reader = keyrot::make_key_reader(in, keyrot::format::csv, ro, warn);
    std::string name;
    keyrot::raw_key raw;
    std::size_t keys = 0;
    while (reader->next(name, raw)) ++keys;
    return keys;
}

/// Prints `frames` rows of `columns` numbers into `path`.
void print_all(const std::string& path, std::size_t frames, std::size_t columns, bool keyrot_writer) {
    std::vector<double> table(4096);  // numbers of a rotation's digits (17 significant, most of them)
    std::mt19937_64 gen(7);
    std::uniform_real_distribution<double> u(-1, 1);
    for (double& v : table) v = u(gen);
    // An earlier output is freed as keyrot frees the one it replaces, not
    // in this program's time (where the filesystem discards freed blocks).
    struct stat st;
    if (::lstat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode)) keyrot::remove_replaced(path, st.st_size);
    std::FILE* out = std::fopen(path.c_str(), "wb");
    if (!out) {
        std::perror(path.c_str());
        std::exit(2);
    }
    std::vector<char> buffer(1 << 16);
    char* at = buffer.data();
    const auto put = [&](double v, char end) {
        if (buffer.data() + buffer.size() - at < 64) {
            std::fwrite(buffer.data(), 1, static_cast<std::size_t>(at - buffer.data()), out);
            at = buffer.data();
        }
        at = keyrot_writer ? keyrot::write_number(at, v, std::nullopt)
                           : std::to_chars(at, buffer.data() + buffer.size(), v).ptr;
        *at++ = end;
    };
    std::size_t next = 0;
    for (std::size_t f = 0; f < frames; ++f) {
        put(static_cast<double>(f), ',');
        put(static_cast<double>(f) / 24, columns > 2 ? ',' : '\n');
        for (std::size_t c = 2; c < columns; ++c) put(table[next++ % table.size()], c + 1 < columns ? ',' : '\n');
    }
    std::fwrite(buffer.data(), 1, static_cast<std::size_t>(at - buffer.data()), out);
    if (std::fclose(out) != 0) std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 5) {
        std::cerr << "usage: keyrot_floor INPUT.csv OUTPUT FRAMES COLUMNS [to_chars|keyrot]\n";
        return 2;
    }
    const std::string input = argv[1], output = argv[2];
    const auto frames = static_cast<std::size_t>(std::strtoull(argv[3], nullptr, 10));
    const auto columns = static_cast<std::size_t>(std::strtoull(argv[4], nullptr, 10));
    const bool keyrot_writer = argc > 5 && std::string(argv[5]) == "keyrot";
    std::size_t keys = 0;
    std::thread parsing([&] {
        try {
            keys = parse_all(input);
        } catch (const keyrot::error& e) {
            std::cerr << "keyrot_floor: " << e.what() << '\n';
        }
    });
    print_all(output, frames, columns, keyrot_writer);
    parsing.join();
    return keys > 0 ? 0 : 2;
}
