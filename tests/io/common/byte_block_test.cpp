// SPDX-License-Identifier: MIT
// byte_block: what is read in comes back whole and in order, read at once
// or a piece at a time, small or past a huge page.
#include "io/common/byte_block.hpp"

#include <doctest/doctest.h>

#include <cstdint>
#include <sstream>
#include <string>

using namespace keyrot;

namespace {

std::string pattern(std::size_t n) {
    std::string s(n, '\0');
    std::uint32_t x = 12345;
    for (char& c : s) c = static_cast<char>((x = x * 1103515245 + 12345) >> 24);
    return s;
}

}  // namespace

TEST_CASE("byte_block: read at once, small and past a huge page") {
    for (const std::size_t n : {std::size_t{1}, std::size_t{100}, std::size_t{2} << 20, (std::size_t{5} << 20) + 3}) {
        const std::string bytes = pattern(n);
        std::istringstream in(bytes);
        byte_block b;
        CHECK(b.read(in, n));
        CHECK(b.view() == bytes);
        CHECK_FALSE(b.read(in, 10));  // at the end: nothing more, and what was read stays
        CHECK(b.view() == bytes);
    }
}

TEST_CASE("byte_block: a piece at a time, growing, keeps what came before") {
    const std::string bytes = pattern((std::size_t{3} << 20) + 777);  // its room grows past 2 MiB on the way
    std::istringstream in(bytes);
    byte_block b;
    std::size_t reads = 0;
    while (b.read(in, std::size_t{1} << 16)) ++reads;
    CHECK(reads == bytes.size() / (std::size_t{1} << 16) + 1);
    CHECK(b.size() == bytes.size());
    CHECK(b.view() == bytes);
}

TEST_CASE("byte_block: a request larger than the stream holds gives what there is") {
    std::istringstream in("glTF");
    byte_block b;
    CHECK(b.read(in, 1000));
    CHECK(b.view() == "glTF");
    CHECK(byte_block{}.view().empty());
}
