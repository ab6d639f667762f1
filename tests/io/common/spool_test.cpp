// SPDX-License-Identifier: MIT
// byte_spool: bytes set aside in a temporary file come back whole and in order.
#include "io/common/spool.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <string_view>

using namespace keyrot;

namespace {

std::string read_back(byte_spool& s) {
    std::string out;
    s.each_block([&](std::string_view block) { out += block; });
    return out;
}

}  // namespace

TEST_CASE("byte_spool: bytes come back in order, across the blocks that go to the file") {
    byte_spool s;
    std::string expected;
    for (int i = 0; i < 30000; ++i) {  // about 200 KB: several blocks in the file, the rest in memory
        const std::string piece = std::to_string(i * 7919) + (i % 3 ? "," : std::string(1, '\0'));
        s.append(piece);
        expected += piece;
    }
    CHECK(s.size() == expected.size());
    CHECK(read_back(s) == expected);
    CHECK(read_back(s) == expected);  // read back again: the same
}

TEST_CASE("byte_spool: cleared, it takes new bytes over the old") {
    byte_spool s;
    s.append(std::string(100000, 'a'));
    s.clear();
    CHECK(s.size() == 0);
    CHECK(read_back(s).empty());
    s.append("bc");
    CHECK(read_back(s) == "bc");
}

TEST_CASE("byte_spool: holds_at compares a range, in the file or in memory or across both, with another spool") {
    byte_spool big;
    std::string bytes;
    for (int i = 0; i < 40000; ++i) bytes += std::to_string(i * 31) + ';';  // about 230 KB: file and memory
    big.append(bytes);
    const auto spool_of = [](std::string_view text) {
        auto s = std::make_unique<byte_spool>();
        s->append(text);
        return s;
    };
    for (const std::size_t at : {std::size_t{0}, std::size_t{65530}, std::size_t{100000}, bytes.size() - 9}) {
        CAPTURE(at);
        const std::size_t n = std::min<std::size_t>(90000, bytes.size() - at);
        CHECK(big.holds_at(at, *spool_of(std::string_view(bytes).substr(at, n))));
        std::string changed = bytes.substr(at, n);
        changed.back() ^= 1;
        CHECK_FALSE(big.holds_at(at, *spool_of(changed)));
    }
    CHECK_FALSE(big.holds_at(bytes.size() - 3, *spool_of(bytes.substr(bytes.size() - 3) + "x")));  // past the end
    CHECK(big.holds_at(bytes.size(), *spool_of("")));
}
