// SPDX-License-Identifier: MIT
// The line reader: lines split at '\n' whatever the chunk size, "\r\n"
// and a byte-order mark dropped, put_back, and the --max-bytes limit.
#include "io/common/line_reader.hpp"

#include <doctest/doctest.h>

#include <sstream>
#include <string>
#include <vector>

#include "keyrot/error.hpp"

using namespace keyrot;

namespace {

/// Every line of `text`, as next() gives them.
std::vector<std::string> lines_of(const std::string& text, std::size_t max_line = 1 << 20) {
    std::istringstream in(text);
    line_reader lines(in, max_line, "in.csv");
    std::vector<std::string> got;
    for (std::string_view line; lines.next(line);) {
        got.emplace_back(line);
        CHECK(lines.number() == got.size());
    }
    return got;
}

using list = std::vector<std::string>;

}  // namespace

TEST_CASE("line_reader: lines, with or without a final newline, empty lines kept") {
    CHECK(lines_of("").empty());
    CHECK(lines_of("\n") == list{""});
    CHECK(lines_of("a,b\n1,2\n") == list{"a,b", "1,2"});
    CHECK(lines_of("a,b\n1,2") == list{"a,b", "1,2"});
    CHECK(lines_of("a\n\n\nb\n") == list{"a", "", "", "b"});
}

TEST_CASE("line_reader: \"\\r\\n\" ends a line as '\\n' does, and crlf() says so") {
    std::istringstream in("a\r\nb\nc\r\n\r");
    line_reader lines(in, 100, "in.csv");
    std::string_view line;
    REQUIRE(lines.next(line));
    CHECK(line == "a");
    CHECK(lines.crlf());
    REQUIRE(lines.next(line));
    CHECK(line == "b");
    CHECK_FALSE(lines.crlf());
    REQUIRE(lines.next(line));
    CHECK(line == "c");
    CHECK(lines.crlf());
    REQUIRE(lines.next(line));  // a last line of one '\r' is an empty line
    CHECK(line == "");
    CHECK_FALSE(lines.next(line));
}

TEST_CASE("line_reader: a UTF-8 byte-order mark is skipped at the start only") {
    CHECK(lines_of("\xEF\xBB\xBFtime,qw\n0,1\n") == list{"time,qw", "0,1"});
    CHECK(lines_of("time\n\xEF\xBB\xBF" "0\n") == list{"time", "\xEF\xBB\xBF" "0"});
    CHECK(lines_of("\xEF\xBB\xBF").empty());
}

TEST_CASE("line_reader: lines across chunk boundaries and longer than a chunk are whole") {
    // The reader takes the stream in chunks of 64 KiB: lines of every length
    // around that size, some of several chunks, come back byte for byte.
    list expected;
    std::string text;
    for (const std::size_t length : {1u, 65535u, 65536u, 65537u, 7u, 200000u, 0u, 131071u, 3u}) {
        expected.push_back(std::string(length, static_cast<char>('a' + expected.size())));
        text += expected.back() + (expected.size() % 2 ? "\n" : "\r\n");
    }
    CHECK(lines_of(text) == expected);
    REQUIRE(text.back() == '\n');
    text.pop_back();  // no final newline
    CHECK(lines_of(text) == expected);
}

TEST_CASE("line_reader: put_back gives the last line again, with its number") {
    std::istringstream in("header\nkey 1\nkey 2\n");
    line_reader lines(in, 100, "in.csv");
    std::string_view line;
    REQUIRE(lines.next(line));
    lines.put_back();
    REQUIRE(lines.next(line));
    CHECK(line == "header");
    CHECK(lines.number() == 1);
    REQUIRE(lines.next(line));
    CHECK(line == "key 1");
    lines.put_back();
    REQUIRE(lines.next(line));
    CHECK(line == "key 1");
    CHECK(lines.number() == 2);
    REQUIRE(lines.next(line));
    CHECK(line == "key 2");
    CHECK(lines.number() == 3);
    CHECK_FALSE(lines.next(line));
}

TEST_CASE("line_reader: a line longer than max_line stops with its source and number") {
    CHECK(lines_of("0123456789\n0123456789\n", 10) == list{"0123456789", "0123456789"});
    std::istringstream in("short\n" + std::string(100000, 'x') + "\nafter\n");
    line_reader lines(in, 1000, "walk.csv");
    std::string_view line;
    REQUIRE(lines.next(line));
    try {
        lines.next(line);
        FAIL("no error for a line of 100000 bytes");
    } catch (const input_error& e) {
        CHECK(std::string(e.what()) ==
              "walk.csv:2: line longer than 1000 bytes: expected the lines of a keyframe table "
              "(--max-bytes N raises the limit)");
    }
}
