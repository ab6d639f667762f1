// SPDX-License-Identifier: MIT
// --output-dir's names: each input's output there with the output format's
// extension, and the checks made before anything is written.
#include "app/output_names.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "helpers.hpp"
#include "keyrot/error.hpp"

using namespace keyrot;
using namespace keyrot::detail;

namespace {

/// The message check_output_names stops with; "" when the names pass.
std::string problem(const options& o, const std::vector<std::string>& inputs) {
    try {
        check_output_names(o, inputs);
    } catch (const usage_error& e) {
        return e.what();
    }
    return "";
}

options to_dir(const std::string& dir, std::optional<format> to = std::nullopt) {
    options o;
    o.output_dir = dir;
    o.to = to;
    return o;
}

}  // namespace

TEST_CASE("in_output_dir: the input's file name, in the directory, with the output's extension") {
    CHECK(in_output_dir("out", "walks/a.json", format::csv) == std::filesystem::path("out/a.csv"));
    CHECK(in_output_dir("out", "a.csv", format::ndjson) == std::filesystem::path("out/a.ndjson"));
    CHECK(in_output_dir("out", "takes/run.2.bvh", format::glb) == std::filesystem::path("out/run.2.glb"));
    CHECK(in_output_dir("/tmp/x", "noext", format::json) == std::filesystem::path("/tmp/x/noext.json"));
}

TEST_CASE("check_output_names: distinct names pass") {
    CHECK(problem(to_dir("out"), {"a.csv", "b.csv", "c.json"}) == "");
    // Same stem, different known output formats: a.csv and a.json stay apart.
    CHECK(problem(to_dir("out"), {"a.csv", "x/a.json"}) == "");
}

TEST_CASE("check_output_names: two inputs to one output name") {
    CHECK(problem(to_dir("out"), {"walks/a.csv", "runs/a.csv"}) ==
          "--output-dir out: 'walks/a.csv' and 'runs/a.csv' would both be written to 'out/a.csv': expected inputs "
          "with distinct names");
    // --to makes one extension of all: a.csv and a.json collide.
    CHECK(problem(to_dir("out", format::ndjson), {"a.csv", "a.json"}) ==
          "--output-dir out: 'a.csv' and 'a.json' would both be written to 'out/a.ndjson': expected inputs "
          "with distinct names");
    // An output format that would be sniffed is not known: the same stem collides.
    CHECK(problem(to_dir("out"), {"a.csv", "a.keys"}) ==
          "--output-dir out: 'a.csv' and 'a.keys' would both be written to 'out/a.*': expected inputs "
          "with distinct names");
}

TEST_CASE("check_output_names: no output replaces an input, by file identity, not by name") {
    const keyrot::test::scratch s;
    const std::string input = s.file("walk.csv", "time,qw,qx,qy,qz\n0,1,0,0,0\n");
    CHECK(problem(to_dir(s.dir.string()), {input}) ==
          "--output-dir " + s.dir.string() + ": the output of '" + input + "' would replace the input '" + input + "'");
    // The same directory by another spelling is the same file.
    const std::string other_spelling = (s.dir / ".").string();
    CHECK(problem(to_dir(other_spelling), {input}) != "");
    // Another output format writes beside it.
    CHECK(problem(to_dir(s.dir.string(), format::json), {input}) == "");
    // A hard link to an input is that input.
    std::filesystem::create_directories(s.dir / "out");
    std::filesystem::create_hard_link(input, s.dir / "out" / "take.csv");
    const std::string link_input = (s.dir / "take.csv").string();
    std::filesystem::copy_file(input, link_input);
    CHECK(problem(to_dir((s.dir / "out").string()), {link_input}) == "");  // a copy is another file
    std::filesystem::remove(link_input);
    std::filesystem::create_hard_link(input, link_input);
    CHECK(problem(to_dir((s.dir / "out").string()), {input, link_input}) ==
          "--output-dir " + (s.dir / "out").string() + ": the output of '" + link_input + "' would replace the input '" +
          input + "'");
}

TEST_CASE("check_output_names: standard input is no file to replace") {
    CHECK(problem(to_dir("."), {"-"}) == "");
}
