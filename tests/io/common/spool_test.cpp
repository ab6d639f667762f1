// byte_spool: bytes set aside in a temporary file come back whole and in order.
#include "io/common/spool.hpp"

#include <doctest/doctest.h>

#include <string>

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
