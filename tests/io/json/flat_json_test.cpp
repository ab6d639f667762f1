// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <fmt/format.h>

#include <random>
#include <string>
#include <vector>

#include "io/json/flat_json.hpp"
#include "json_same.hpp"

using keyrot::flat_json;
using keyrot::test::same_json;

namespace {

/// flat_json takes `text`, and nlohmann-json reads the same value from it.
bool taken_as_nlohmann(flat_json& line, const std::string& text) {
    if (!line.parse(text)) return false;
    try {
        return same_json(nlohmann::ordered_json::parse(text), line.root());
    } catch (const nlohmann::json::exception&) {
        return false;  // flat_json took what nlohmann-json refuses
    }
}

}  // namespace

TEST_CASE("flat_json takes key lines, numbers and literals as nlohmann-json reads them") {
    flat_json line;
    for (const std::string& text : std::vector<std::string>{
             R"({"time": 0, "quat": [1, 0, 0, 0]})",
             R"({"track": "left knee", "frame": 12, "time": 0.5, "axis": [0, 0, 1], "angle": 90})",
             R"({"time":1.25,"rotvec":[0.1,-0.2,3e-3],"translation":[1,2,3]})",
             R"({"time": 2, "matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]})",
             R"({"time": 2, "quat": {"w": 1, "x": 0, "y": 0, "z": 0}, "note": null, "ok": true, "bad": false})",
             "\t{ \"time\" :\r\n 3 , \"euler\" : [ 10 , 20 , 30 ] }  ",
             "[]", "{}", "[[], {}, [[]]]", "\"\"", "\"a string, with: [brackets]\"", "true", "false", "null",
             // -0 is nlohmann-json's integer 0, a +0.0; -0.0 and -0e0 keep the sign.
             "0", "-0", "-0.0", "-0e0", "0.1", "1e-5", "1E+5", "2.5e3", "-12.75",
             // Integers past 2^53, int64 and uint64 round to the nearest double.
             "9007199254740993", "-9223372036854775808", "-9223372036854775809", "18446744073709551615",
             "18446744073709551617", "123456789012345678901234567890",
             // Halfway cases, the smallest normal and subnormal, the largest double.
             "0.30000000000000004", "2.2250738585072014e-308", "4.9406564584124654e-324", "1.7976931348623157e308",
             "9007199254740993.0000000000000000000001",
             // UTF-8 and a DEL, which JSON leaves unescaped.
             "\"caf\xc3\xa9\"", "{\"\xe3\x82\xab\xe3\x83\xa1\xe3\x83\xa9\": \"\xf0\x9f\xa6\xb4\"}", "\"a\x7f\"",
             // Escapes, decoded: each kind, \u in both cases, the ends of each UTF-8 length,
             // a surrogate pair, NUL; in names too; beside UTF-8.
             R"("\" \\ \/ \b \f \n \r \t")", R"("\u00e9\u00E9\u0041")", R"("\u0000\u007f\u0080\u07ff\u0800\uffff")",
             R"("\ud800\udc00 \ud83e\uddb4 \uDBFF\uDFFF")", R"({"caf\u00e9": 1, "\"": [2], "\\": {"\/": "\n"}})",
             "\"caf\xc3\xa9 \\u00e9\"", R"(["a\"b", "c"])", R"({"a": "\\", "b": "\\\""})",
         }) {
        CAPTURE(text);
        CHECK(taken_as_nlohmann(line, text));
    }
    REQUIRE(line.parse("-0"));
    CHECK(!std::signbit(line.root().number()));
    REQUIRE(line.parse("-0.0"));
    CHECK(std::signbit(line.root().number()));
}

TEST_CASE("flat_json declines bad escapes, what is not UTF-8, duplicate names, deep or wide values and every syntax error") {
    flat_json line;
    const std::string deep = std::string(9, '[') + std::string(9, ']');
    // 257 members: past what it checks for duplicates.
    std::string wide = "{\"m0\": 0";
    for (int i = 1; i <= 256; ++i) wide += fmt::format(", \"m{}\": 0", i);
    wide += "}";
    REQUIRE(line.parse(wide.substr(0, wide.rfind(',')) + "}"));
    for (const std::string& text : std::vector<std::string>{
             // nlohmann-json takes these, and words them or reads them itself.
             R"({"a": 1, "a": 2})", R"({"a": 1, "\u0061": 2})", deep, wide,
             // Escapes nlohmann-json refuses: unknown, cut short, not hex, a lone surrogate
             // either way, a high one followed by other than a low one; a raw tab.
             R"("\x")", R"("\a")", R"("\U00e9")", R"("\")", R"("\u")", R"("\u00e")", R"("\u00g9")", R"("\ud800")",
             R"("\udc00")", R"("\ud800\u0041")", R"("\ud800\ud800")", R"("\ud800x")", R"("\ud800\")", "\"\\u00e9\t\"",
             // Escapes beside bytes that are not UTF-8.
             "\"\\u00e9\xc3\"", "\"\xff\\n\"",
             // Not UTF-8: overlong, a surrogate, cut short, a lone continuation byte, past U+10FFFF, 5 bytes.
             "\"\xc0\xaf\"", "\"\xed\xa0\x80\"", "\"\xc3\"", "\"\xe3\x82\"", "\"\x80\"", "\"\xf4\x90\x80\x80\"",
             "\"\xf8\x88\x80\x80\x80\"", "{\"\xff\": 1}",
             "1e999", "-1e999",
             // Syntax errors, which nlohmann-json words.
             "", " ", "01", "-01", "1.", ".5", "+1", "-", "1e", "1e+", "0x10", "1.5.2", "Infinity", "NaN",
             "[1,]", "[,1]", "[1 2]", "{\"a\"}", "{\"a\":}", "{a: 1}", "{\"a\": 1,}", "{\"a\": 1 \"b\": 2}",
             "{'a': 1}", "tru", "nul", "falsey", "\"abc", "\"a\x01\"", "{} x", "[]]", "{}}", "[", "{",
             "\v1",
         }) {
        CAPTURE(text);
        CHECK(!line.parse(text));
    }
    // A bound on the values, as for an NDJSON line: 128 values, not 129.
    flat_json bounded(128);
    std::string array = "[0";
    for (int i = 1; i < 127; ++i) array += ",0";
    CHECK(bounded.parse(array + "]"));
    CHECK(!bounded.parse(array + ",0]"));
    CHECK(line.parse(array + ",0]"));
}

TEST_CASE("flat_json against nlohmann-json on random lines, valid and broken") {
    // Random values from a few spellings each, one in two with one byte
    // changed, dropped or added: whatever flat_json takes, nlohmann-json must
    // read as the same value.
    std::mt19937 gen(20261122);
    const std::vector<std::string> numbers = {"0", "-0", "1", "-2.5", "1e3", "6.02E+23", "1e-320", "0.1",
                                              "18446744073709551616", "-7", "3.14159265358979"};
    const std::vector<std::string> names = {"time", "quat", "a", "", "x y", "track", "caf\xc3\xa9", "\xe3\x82\xab",
                                            R"(caf\u00e9)", R"(\"q\\)", R"(\ud83e\uddb4)", R"(\u0061)"};
    const auto pick = [&](const std::vector<std::string>& from) {
        return from[std::uniform_int_distribution<std::size_t>(0, from.size() - 1)(gen)];
    };
    const auto random_value = [&](const auto& self, int depth) -> std::string {
        switch (std::uniform_int_distribution<int>(0, depth > 3 ? 2 : 5)(gen)) {
            case 0:
            case 1: return pick(numbers);
            case 2: return std::vector<std::string>{"true", "false", "null", "\"s\"", "\"\"", R"("\n\u00e9")"}[gen() % 6];
            case 3:
            case 4: {
                std::string out = "[";
                for (auto i = gen() % 5; i > 0; --i) {
                    out += self(self, depth + 1);
                    out += i > 1 ? ", " : "";
                }
                return out += "]";
            }
            default: {
                std::string out = "{";
                for (auto i = gen() % 4; i > 0; --i) {
                    out += '"';
                    out += pick(names);
                    out += "\": ";
                    out += self(self, depth + 1);
                    out += i > 1 ? "," : "";
                }
                return out += "}";
            }
        }
    };
    const std::string bytes = "[]{},:\"-+.eE0123456789 \\tfnuabdD\xc3\xa9\x82\xed";
    flat_json line;
    int taken = 0, broken_taken = 0;
    for (int n = 0; n < 20000; ++n) {
        std::string text = random_value(random_value, 0);
        const bool broken = n % 2 == 1;
        if (broken) {
            const std::size_t at = gen() % (text.size() + 1);
            const char c = bytes[gen() % bytes.size()];
            switch (gen() % 3) {
                case 0: text.insert(at, 1, c); break;
                case 1: if (at < text.size()) text.erase(at, 1); break;
                default: if (at < text.size()) text[at] = c; break;
            }
        }
        CAPTURE(text);
        if (!line.parse(text)) continue;
        ++taken;
        broken_taken += broken;
        CHECK(taken_as_nlohmann(line, text));
    }
    // Not a vacuous check: most valid lines are taken (the rest have duplicate
    // names), and so are the changes that leave a line valid.
    CHECK(taken > 8000);
    CHECK(broken_taken > 1000);
}
