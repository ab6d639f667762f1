// SPDX-License-Identifier: MIT
// The commands run in-process, with streams and a scratch directory.
#include "app/app.hpp"

#include <doctest/doctest.h>

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli.hpp"
#include "helpers.hpp"

using namespace keyrot;
namespace fs = std::filesystem;
using keyrot::test::scratch;

namespace {

struct result {
    int status;
    std::string out, err;
};

result run_with(const options& o, const std::string& input = "") {
    std::istringstream in(input);
    std::ostringstream out, err;
    const int status = run(o, in, out, err);
    return {status, out.str(), err.str()};
}

options parse(std::vector<const char*> args) {
    args.insert(args.begin(), "keyrot");
    std::ostringstream out;
    return *parse_command_line(static_cast<int>(args.size()), args.data(), out);
}

const char* two_keys = "time,ax,ay,az,angle\n0,0,0,1,0\n1,0,0,1,90\n";

}  // namespace

TEST_CASE("resample from standard input to standard output") {
    const result r = run_with(parse({"resample", "--fps", "4", "--precision", "6"}), two_keys);
    CHECK(r.status == 0);
    CHECK(r.err.empty());
    // plain: its frames carry their times, so nothing needs saying
    CHECK(r.out == "frame,time,ax,ay,az,angle\n0,0,1,0,0,0\n1,0.25,0,0,1,22.5\n2,0.5,0,0,1,45\n3,0.75,0,0,1,67.5\n4,1,0,0,1,90\n");
}

TEST_CASE("convert keeps the keys and their frame column, with their times beside it") {
    const result r = run_with(parse({"convert", "--rep", "quat", "--precision", "4"}),
                              "frame,ax,ay,az,angle\n0,0,0,1,0\n6,0,0,1,90\n");
    // at the default rate: 6 / 24 = 0.25 s
    CHECK(r.out == "frame,time,qw,qx,qy,qz\n0,0,1,0,0,0\n6,0.25,0.7071,0,0,0.7071\n");
    const result j = run_with(parse({"convert", "--to", "json", "--rep", "rotvec"}), "time,qw,qx,qy,qz\n0.5,1,0,0,0\n");
    CHECK(j.out == "{\"rep\": \"rotvec\", \"angles\": \"degrees\", \"keys\": [\n{\"time\": 0.5, \"rotvec\": [0, 0, 0]}]}\n");
    const result f = run_with(parse({"convert", "--to", "json", "--rep", "rotvec"}), "frame,qw,qx,qy,qz\n12,1,0,0,0\n");
    CHECK(f.out == "{\"rep\": \"rotvec\", \"angles\": \"degrees\", \"keys\": [\n{\"frame\": 12, \"time\": 0.5, \"rotvec\": [0, 0, 0]}]}\n");
    // a rate the user gave times the frames: no line of settings is needed to read them back
    const result stated = run_with(parse({"convert", "--rep", "quat", "--key-fps", "30"}), "frame,qw,qx,qy,qz\n3,1,0,0,0\n");
    CHECK(stated.out == "frame,time,qw,qx,qy,qz\n3,0.1,1,0,0,0\n");
}

TEST_CASE("resample output chains into convert, in every format") {
    for (const char* to : {"csv", "json", "ndjson"}) {
        CAPTURE(std::string(to));
        const result first = run_with(parse({"resample", "--to", to, "--rep", "matrix4"}), two_keys);
        REQUIRE(first.status == 0);
        const result second = run_with(parse({"convert", "--to", "csv", "--rep", "axis-angle", "--precision", "9"}), first.out);
        CHECK(second.status == 0);
        // frame 24 = 1 s is the last key; both time columns and matrix4's
        // zero translation come along
        CHECK(second.out.starts_with("frame,time,ax,ay,az,angle,tx,ty,tz\n"));
        CHECK(second.out.find("\n24,1,0,0,1,90,0,0,0\n") != std::string::npos);
    }
}

TEST_CASE("Euler output needs a sequence; --out-euler defaults to --euler") {
    CHECK_THROWS_AS(run_with(parse({"convert", "--rep", "euler"}), two_keys), usage_error);
    const result r = run_with(parse({"convert", "--rep", "euler", "--euler", "ZYX"}), two_keys);
    CHECK(r.out == "time,e1,e2,e3\n0,0,0,0\n1,90,0,0\n");
    // the document's own sequence serves too
    const result j = run_with(parse({"convert", "--rep", "euler", "--to", "csv"}),
                              R"({"euler": "xyz", "keys": [{"time": 0, "euler": [0, 0, 30]}]})");
    REQUIRE(j.out.starts_with("time,e1,e2,e3\n0,0,0,"));
    CHECK(std::fabs(std::stod(j.out.substr(j.out.rfind(',') + 1)) - 30) <= 8e-15);
}

TEST_CASE("glb is not written to a terminal, and is written to a file or a pipe") {
    scratch s;
    for (const char* command : {"resample", "convert", "reduce"}) {
        CAPTURE(std::string(command));
        options o = parse({command, "--to", "glb"});
        o.terminal_out = true;
        CHECK_THROWS_WITH_AS(run_with(o, two_keys),
                             "glb is binary, and standard output is a terminal: expected -o FILE.glb, a pipe or > FILE "
                             "(--to gltf writes text; -o /dev/stdout writes glb here all the same)",
                             usage_error);
        o.terminal_out = false;  // a pipe or a file
        CHECK(run_with(o, two_keys).out.starts_with("glTF"));
        o = parse({command, "--to", "gltf"});  // text
        o.terminal_out = true;
        CHECK(run_with(o, two_keys).out.starts_with("{\"asset\""));
        const std::string target = (s.dir / (std::string(command) + ".glb")).string();
        o = parse({command, "-o", target.c_str()});
        o.terminal_out = true;
        CHECK(run_with(o, two_keys).status == 0);
        CHECK(scratch::read(target).starts_with("glTF"));
    }
    options slerp = parse({"slerp", "1,0,0,0", "0,0,0,1", "-t", "0.5", "--to", "glb"});
    slerp.terminal_out = true;
    CHECK_THROWS_AS(run_with(slerp), usage_error);
}

TEST_CASE("-o writes the file; an error leaves no file and an existing one untouched") {
    scratch s;
    const std::string good = s.file("good.csv", two_keys);
    const std::string bad = s.file("bad.csv", "time,qw,qx,qy,qz\n0,1,0,0,x\n");
    const std::string target = (s.dir / "out.json").string();
    options o = parse({"resample", good.c_str(), "-o", target.c_str()});
    CHECK(run_with(o).status == 0);
    CHECK(scratch::read(target).find("{\"fps\": 24") == 0);  // format from the extension of -o

    std::ofstream(target) << "precious";
    o = parse({"resample", bad.c_str(), "-o", target.c_str()});
    const result r = run_with(o);
    CHECK(r.status == 2);
    CHECK(r.err == "keyrot: " + bad + ":2: column 'qz': expected a finite number, got 'x'\n");
    CHECK(scratch::read(target) == "precious");
    o = parse({"resample", bad.c_str(), "-o", (s.dir / "new.csv").string().c_str()});
    CHECK(run_with(o).status == 2);
    std::size_t files = 0;
    for (const auto& e : fs::directory_iterator(s.dir)) files += e.is_regular_file();
    CHECK(files == 3);  // good.csv, bad.csv, out.json: nothing else, no temporary left
}

TEST_CASE("several inputs: --output-dir, a bad file is skipped and reported, status 2") {
    scratch s;
    const std::string a = s.file("a.csv", two_keys);
    const std::string bad = s.file("bad.json", "{\"keys\": [}");
    const std::string b = s.file("b.json", R"({"keys": [{"time": 0, "quat": [1,0,0,0]}]})");
    CHECK_THROWS_AS(run_with(parse({"resample", a.c_str(), b.c_str()})), usage_error);
    const std::string out_dir = (s.dir / "out").string();
    const result r = run_with(parse({"resample", a.c_str(), bad.c_str(), b.c_str(), "--output-dir", out_dir.c_str(), "--to", "ndjson"}));
    CHECK(r.status == 2);
    CHECK(r.err.find("keyrot: " + bad + ":1:11: invalid JSON") == 0);
    CHECK(fs::exists(s.dir / "out" / "a.ndjson"));
    CHECK(fs::exists(s.dir / "out" / "b.ndjson"));
    CHECK_FALSE(fs::exists(s.dir / "out" / "bad.ndjson"));
}

TEST_CASE("--jobs: files in parallel, messages in input order") {
    scratch s;
    std::vector<std::string> files;
    for (int i = 0; i < 8; ++i) {
        const bool bad = i == 1 || i == 6;
        files.push_back(s.file(fmt::format("f{}.csv", i), bad ? "time,qw,qx,qy,qz\n0,x,0,0,0\n" : two_keys));
    }
    const std::string out_dir = (s.dir / "out").string();
    std::vector<const char*> args = {"resample", "--output-dir", out_dir.c_str(), "--jobs", "3"};
    for (const auto& f : files) args.push_back(f.c_str());
    const result r = run_with(parse(args));
    CHECK(r.status == 2);
    // (then how many of them failed)
    CHECK(r.err == "keyrot: " + files[1] + ":2: column 'qw': expected a finite number, got 'x'\n" + "keyrot: " + files[6] +
                       ":2: column 'qw': expected a finite number, got 'x'\n" + "keyrot: 2 of 8 files failed\n");
    for (int i = 0; i < 8; ++i) CHECK(fs::exists(s.dir / "out" / fmt::format("f{}.csv", i)) == (i != 1 && i != 6));
    CHECK(scratch::read(s.dir / "out" / "f7.csv") == scratch::read(s.dir / "out" / "f0.csv"));
}

TEST_CASE("command-line checks") {
    auto usage = [](std::vector<const char*> args) {
        try {
            parse(std::move(args));
        } catch (const usage_error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(usage({"resample", "--fps", "0"}) == "--fps: expected a positive frame rate, got 0");
    CHECK(usage({"resample", "--fps", "-24"}).find("--fps") != std::string::npos);
    CHECK(usage({"resample", "--fps", "nan"}).find("--fps") != std::string::npos);
    CHECK(usage({"resample", "--fps", "inf"}).find("--fps") != std::string::npos);
    CHECK(usage({"resample", "--method", "bicubic"}).find("--method") != std::string::npos);
    CHECK(usage({"resample", "--rep", "quaternion"}).find("--rep") != std::string::npos);
    CHECK(usage({"resample", "--precision", "18"}) == "--precision: expected 0 to 17 digits, got 18");
    CHECK(usage({"resample", "--euler", "XXY"}).find("--euler: expected three axes") == 0);
    CHECK(usage({"convert", "--method", "slerp"}).find("--method") != std::string::npos);  // resample only
    CHECK(usage({"resample", "--out-degrees", "--out-radians"}).find("excludes") != std::string::npos);
    CHECK(usage({}).find("expected a command: resample, convert") == 0);
    CHECK(usage({"interp", "x"}).find("unknown command 'interp'") == 0);
    CHECK(usage({"compare", "key.csv"}).find("compare: ANSWER is missing") == 0);
    CHECK(usage({"slerp", "1,0,0,0", "0,0,0,1", "-t", "nan"}) == "-t: expected a finite number, got nan");
    // a flag either does what its name says for the command, or is refused
    CHECK(usage({"info", "--to", "csv"}).find("--to") != std::string::npos);
    CHECK(usage({"info", "-o", "info.csv"}).find("info writes text, or JSON") != std::string::npos);
    CHECK(usage({"compare", "a.csv", "b.csv", "--rep", "quat"}).find("not expected") != std::string::npos);
    CHECK(usage({"compare", "a.csv", "b.csv", "--precision", "2"}).find("not expected") != std::string::npos);
    CHECK(usage({"convert", "--jobs", "0"}) == "--jobs: expected 1 to 1024, got 0");
}
