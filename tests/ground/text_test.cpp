// SPDX-License-Identifier: MIT
// The ground floor's text utilities: numbers, UTF-8.
#include "ground/text.hpp"

#include <doctest/doctest.h>

#include <string>

using namespace keyrot;

TEST_CASE("parse_number reads finite doubles only") {
    CHECK(parse_number(" 1.5 ") == 1.5);
    CHECK(parse_number("+2") == 2);
    CHECK(parse_number("-1e-3") == -1e-3);
    for (const char* bad : {"", "abc", "1.5x", "nan", "inf", "-inf", "1e400", "++1", "1 2", "0x10", "-", "--1", "-+1",
                            "- 1", "-nan", "-1e400"}) {
        CAPTURE(bad);
        CHECK_FALSE(parse_number(bad));
    }
    const auto negative_zero = parse_number("-0");
    REQUIRE(negative_zero);
    CHECK((*negative_zero == 0 && std::signbit(*negative_zero)));
    // Too small for a double: the nearest, zero, as the JSON readers and
    // strtod read it (one rule for CSV and JSON); too large stays an error.
    CHECK(parse_number("1e-400") == 0);
    const auto tiny_negative = parse_number("-1e-400");
    REQUIRE(tiny_negative);
    CHECK((*tiny_negative == 0 && std::signbit(*tiny_negative)));
    CHECK(parse_number("4.9e-324") == 4.9e-324);  // the least subnormal is no underflow
}

TEST_CASE("UTF-8 validation") {
    CHECK(is_valid_utf8("hip"));
    CHECK(is_valid_utf8("h\xC3\xBC" "fte"));  // hüfte
    CHECK_FALSE(is_valid_utf8("\xFF"));
    CHECK_FALSE(is_valid_utf8("\xC3"));
    CHECK_FALSE(is_valid_utf8("\xC0\xAF"));          // overlong
    CHECK_FALSE(is_valid_utf8("\xED\xA0\x80"));      // surrogate
    // Lines of 8 bytes and more are first checked a word at a time: a byte
    // of any value at any place of them, and at their end.
    for (std::size_t size = 8; size <= 40; ++size) {
        for (std::size_t at = 0; at < size; ++at) {
            CAPTURE(size);
            CAPTURE(at);
            std::string line(size, 'a');
            CHECK(is_valid_utf8(line));
            line[at] = '\xFF';
            CHECK_FALSE(is_valid_utf8(line));
            line[at] = '\x7F';
            CHECK(is_valid_utf8(line));
            line.replace(at, 1, "\xC3\xBC");  // ü
            CHECK(is_valid_utf8(line));
            line.pop_back();
            CHECK(is_valid_utf8(line) == (at + 1 < line.size()));  // ü cut in half where it was last
        }
    }
}

