// SPDX-License-Identifier: MIT
#include "io/json/json_object.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "keyrot/error.hpp"

using namespace keyrot;

TEST_CASE("json_object writes members in call order, as the reports lay them out") {
    const std::string text = json_object()
                                 .text("track", "hip \"L\"\n")
                                 .count("keys", 3)
                                 .number("tol", 0.1 + 0.2)
                                 .number("whole", 1.0)
                                 .number("none", std::nullopt)
                                 .flag("pass", false)
                                 .raw("first", "[1, 5]")
                                 .object();
    CHECK(text == R"({"track": "hip \"L\"\n", "keys": 3, "tol": 0.30000000000000004, "whole": 1, "none": null, )"
                  R"("pass": false, "first": [1, 5]})");
    // Read back by another parser: the same values, the number to the bit.
    const auto j = nlohmann::json::parse(text);
    CHECK(j["track"] == "hip \"L\"\n");
    CHECK(j["tol"].get<double>() == 0.1 + 0.2);
    CHECK(j["none"].is_null());
    CHECK(j["first"] == nlohmann::json::array({1, 5}));
}

TEST_CASE("json_object's members alone, for an object written in pieces") {
    json_object end;
    CHECK(end.members().empty());
    CHECK(end.object() == "{}");
    end.count("rows", 2).flag("pass", true);
    CHECK("{\"entries\": [], " + end.members() + "}" == R"({"entries": [], "rows": 2, "pass": true})");
}

TEST_CASE("json_number: shortest round trip, never -0, null for none") {
    CHECK(json_number(1e-5) == "1e-05");
    CHECK(json_number(-0.0) == "0");
    CHECK(json_number(std::nullopt) == "null");
    CHECK_THROWS_AS(json_object().text("name", "\xff"), input_error);  // not UTF-8: no invalid JSON written
}
