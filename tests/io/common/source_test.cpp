// SPDX-License-Identifier: MIT
// Inputs: files read in place, standard input kept so that it can be read
// twice, the format by flag, extension or content.
#include "io/common/source.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "helpers.hpp"
#include "keyrot/error.hpp"

using namespace keyrot;

namespace {

std::string all_of(std::istream& in) { return {std::istreambuf_iterator<char>(in), {}}; }

}  // namespace

TEST_CASE("input_source: a file, read from the start as often as asked") {
    const keyrot::test::scratch s;
    const std::string path = s.file("keys.json", "[{\"time\": 0, \"quat\": [1, 0, 0, 0]}]\n");
    std::istringstream unused;
    const input_source src(path, unused);
    CHECK(src.source() == path);
    CHECK(src.detect(std::nullopt) == format::json);
    CHECK(src.detect(format::ndjson) == format::ndjson);
    const auto first = src.open();
    const auto second = src.open();
    CHECK(all_of(*first) == all_of(*second));
}

TEST_CASE("input_source: standard input ('-') is kept, read twice, named <stdin>, sniffed") {
    std::istringstream in("time,qw,qx,qy,qz\n0,1,0,0,0\n");
    const input_source src(std::string(standard_stream), in);
    CHECK(src.source() == "<stdin>");
    CHECK(src.detect(std::nullopt) == format::csv);
    CHECK(all_of(*src.open()) == "time,qw,qx,qy,qz\n0,1,0,0,0\n");
    CHECK(all_of(*src.open()) == "time,qw,qx,qy,qz\n0,1,0,0,0\n");
}

TEST_CASE("input_source: a missing file is one line naming it; a file that changes between readings is an error") {
    std::istringstream unused;
    try {
        const input_source src("/nonexistent/keys.csv", unused);
        FAIL("no error");
    } catch (const error& e) {
        CHECK(std::string(e.what()) == "cannot read '/nonexistent/keys.csv': No such file or directory");
    }
    const keyrot::test::scratch s;
    const std::string path = s.file("keys.csv", "time,qw,qx,qy,qz\n0,1,0,0,0\n");
    const input_source src(path, unused);
    all_of(*src.open());
    std::ofstream(path, std::ios::app) << "1,1,0,0,0\n";
    CHECK_THROWS_AS(all_of(*src.open()), error);
}

TEST_CASE("'-' is the one name of the standard streams") {
    CHECK(is_standard_stream("-"));
    CHECK_FALSE(is_standard_stream("./-"));
    CHECK(source_name("-") == "<stdin>");
    CHECK(source_name("a.csv") == "a.csv");
}
