// SPDX-License-Identifier: MIT
// Reading CSV: columns, comments, quoting, the fast path for plain rows.
#include "io/csv/csv.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <sstream>

#include "helpers.hpp"
#include "reading.hpp"

using namespace keyrot;
using keyrot::test::error_of;
using keyrot::test::read;
using keyrot::test::read_keys;

TEST_CASE("formats by name, extension and content") {
    CHECK(format_of_path("a/b.CSV") == format::csv);
    CHECK(format_of_path("x.jsonl") == format::ndjson);
    CHECK(format_of_path("x.ndjson") == format::ndjson);
    CHECK_FALSE(format_of_path("dir.json/file"));
    CHECK(sniff_format("time,qw\n") == format::csv);
    CHECK(sniff_format("  {\n \"keys\": []}") == format::json);
    CHECK(sniff_format("[{\"time\": 0}]") == format::json);
    CHECK(sniff_format("{\"time\": 0, \"quat\": [1,0,0,0]}\n{\"time\": 1, \"quat\": [1,0,0,0]}\n") == format::ndjson);
    CHECK(sniff_format("{\"keys\": []}\n") == format::json);
    CHECK(format_of_path("take.BVH") == format::bvh);
    CHECK(sniff_format("\xEF\xBB\xBF\r\nHIERARCHY\r\nROOT Hips\r\n") == format::bvh);
    CHECK(sniff_format("hierarchy\n") == format::bvh);
}

TEST_CASE("CSV: columns in any order and case, comments, blank lines, BOM, CRLF") {
    const std::string text = "\xEF\xBB\xBF# comment\r\n\r\n QZ , Time,qx,QW,qy\r\n1,0,0,0,0\r\n  # another\n0,1,0,1,0";
    const auto doc = read(text, format::csv);
    REQUIRE(doc.tracks.size() == 1);
    CHECK_FALSE(doc.named);
    const auto k = read_keys(text, format::csv);
    REQUIRE(k.size() == 2);
    CHECK(*k[0].second.time == 0);
    CHECK(k[0].second.values[0] == 0);  // w
    CHECK(k[0].second.values[3] == 1);  // z
    CHECK(k[1].second.values[0] == 1);
    CHECK(k[1].second.at.line == 6);
    CHECK(doc.tracks[0].keys[1].rotation.w == 1);
}

TEST_CASE("CSV: tracks in order of first appearance, translations optional per key") {
    const auto doc = read("track,time,rx,ry,rz,tx,ty,tz\nb,0,0,0,0,1,2,3\na,0,0,0,0,,,\nb,1,0,0,0,,,\n", format::csv);
    CHECK(doc.named);
    REQUIRE(doc.tracks.size() == 2);
    CHECK(doc.tracks[0].name == "b");
    CHECK(doc.tracks[0].keys.size() == 2);
    CHECK(doc.tracks[0].keys[0].translation->z == 3);
    CHECK_FALSE(doc.tracks[0].keys[1].translation);
    CHECK(doc.tracks[1].name == "a");
}

TEST_CASE("CSV: scale columns sx sy sz, optional per key, beside a 4x4 matrix too") {
    const auto doc = read("time,qw,qx,qy,qz,sx,sy,sz\n0,1,0,0,0,1,2,3\n1,1,0,0,0,,,\n", format::csv);
    CHECK(doc.tracks[0].keys[0].scale->y == 2);
    CHECK_FALSE(doc.tracks[0].keys[0].translation);
    CHECK_FALSE(doc.tracks[0].keys[1].scale);
    const auto m4 = read("time,m00,m01,m02,m03,m10,m11,m12,m13,m20,m21,m22,m23,m30,m31,m32,m33,sx,sy,sz\n"
                         "0,1,0,0,4,0,1,0,5,0,0,1,6,0,0,0,1,2,2,2\n",
                         format::csv);
    CHECK(m4.tracks[0].keys[0].translation->x == 4);
    CHECK(m4.tracks[0].keys[0].scale->z == 2);
    CHECK(error_of("time,qw,qx,qy,qz,sx,sy\n0,1,0,0,0,1,1\n", format::csv) ==
          "in:1: scale needs all of the columns sx sy sz");
    CHECK(error_of("time,qw,qx,qy,qz,sx,sy,sz\n0,1,0,0,0,1,,1\n", format::csv) ==
          "in:2: columns sx sy sz: expected three numbers or three empty cells");
}

TEST_CASE("CSV: morph weights w0 .. wN-1, a track with fewer leaving the last cells empty") {
    const auto doc = read("track,time,qw,qx,qy,qz,W1,w0,w2\nface,0,1,0,0,0,0.5,0.25,1\n"
                          "face,1,1,0,0,0,1,0,0\neye,0,1,0,0,0,,2,\narm,0,1,0,0,0,,,\n",
                          format::csv);
    REQUIRE(doc.tracks.size() == 3);
    CHECK(doc.tracks[0].keys[0].weights == morph_weights{0.25, 0.5, 1});  // (the fast path)
    CHECK(doc.tracks[1].keys[0].weights == morph_weights{2});
    CHECK(doc.tracks[2].keys[0].weights.empty());
    CHECK(error_of("time,qw,qx,qy,qz,w1\n0,1,0,0,0,1\n", format::csv) ==
          "in:1: column 'w1' without 'w0': expected the morph weights' columns w0 to wN-1, each once");
    CHECK(error_of("time,qw,qx,qy,qz,w0,w1\n0,1,0,0,0,,1\n", format::csv) ==
          "in:2: column 'w1' after an empty 'w0': expected the weights as numbers from w0 on, and the columns "
          "after them empty");
    CHECK(error_of("time,qw,qx,qy,qz,w0,w1\n0,1,0,0,0,1,1\n1,1,0,0,0,1,\n", format::csv) ==
          "in:3: 1 morph weights after a key with 2: expected as many on every key of a track");
}

TEST_CASE("CSV: every representation's columns") {
    CHECK(read_keys("time,ax,ay,az,angle\n0,0,0,1,90\n", format::csv)[0].second.kind == rep::axis_angle);
    CHECK(read("time,e1,e2,e3\n0,1,2,3\n", format::csv).tracks[0].keys[0].given_as == rep::euler);
    const auto m = read_keys("frame,m00,m01,m02,m10,m11,m12,m20,m21,m22\n5,1,0,0,0,1,0,0,0,1\n", format::csv);
    CHECK(m[0].second.kind == rep::matrix);
    CHECK(*m[0].second.frame == 5);
    const auto m4 = read("time,m00,m01,m02,m03,m10,m11,m12,m13,m20,m21,m22,m23,m30,m31,m32,m33\n"
                         "0,1,0,0,4,0,1,0,5,0,0,1,6,0,0,0,1\n",
                         format::csv);
    CHECK(m4.tracks[0].keys[0].given_as == rep::matrix4);
    CHECK(m4.tracks[0].keys[0].translation->x == 4);
}

TEST_CASE("CSV errors name the line and what was expected") {
    CHECK(error_of("time,qw,qx,qy,qz\n0,1,0,0,0\n0.5,abc,0,0,0\n", format::csv) ==
          "in:3: column 'qw': expected a finite number, got 'abc'");
    CHECK(error_of("time,qw,qx,qy,qz\n0,1,0,0\n", format::csv) == "in:2: expected 5 cells as in the header, got 4");
    CHECK(error_of("time,qw,qx,qy,qz\n0,nan,0,0,0\n", format::csv).find("in:2: column 'qw'") == 0);
    CHECK(error_of("time,qw,qx,qy,qz\n0,1e400,0,0,0\n", format::csv).find("got '1e400'") != std::string::npos);
    CHECK(error_of("time,qw,qx,qy,qz,ax,ay,az,angle\n", format::csv) ==
          "in:1: columns of two rotation representations (quat and axis-angle): expected one");
    CHECK(error_of("time,qw,qx,qy\n", format::csv) == "in:1: missing column 'qz': quat needs qw qx qy qz");
    CHECK(error_of("time,qw,qx,qy,qw\n", format::csv) == "in:1: column 'qw' appears twice: expected each column once");
    CHECK(error_of(",time,qw,qx,qy,qz,QW\n", format::csv) == "in:1: column 'qw' appears twice: expected each column once");
    CHECK(error_of("qw,qx,qy,qz\n", format::csv) == "in:1: no time column: expected a 'time' or 'frame' column");
    CHECK(error_of("time\tqw\tqx\tqy\tqz\n", format::csv) ==
          "in:1: expected commas (or semicolons) between the columns, got 'time\\x09qw\\x09qx\\x09qy\\x09qz'");
    CHECK(error_of("time,foo\n", format::csv).find("in:1: no rotation columns") == 0);
    CHECK(error_of("", format::csv) == "in: empty input: expected a CSV header and keys");
    CHECK(error_of("# c\ntime,qw,qx,qy,qz\n", format::csv) == "in:2: no keys: expected at least one key");
    CHECK(error_of("time,rx,ry,rz,tx,ty,tz\n0,0,0,0,1,,\n", format::csv).find("in:2: columns tx ty tz") == 0);
    CHECK(error_of("track,time,rx,ry,rz\n\xFF,0,0,0,0\n", format::csv) == "in:2: invalid UTF-8: expected text");
}

namespace {

/// Both empty, or the same double to the bit (-0 is not 0).
bool same_bits(std::optional<double> a, std::optional<double> b) {
    return a.has_value() == b.has_value() && (!a || std::memcmp(&*a, &*b, sizeof(double)) == 0);
}

}  // namespace

TEST_CASE("CSV: a plain row reads as the same row read cell by cell") {
    // Rows of numbers and track names take the fast path, with or without
    // blanks around the cells; with every cell quoted the same row is split
    // into cells and unquoted. All must give the same keys, to the bit.
    std::mt19937_64 gen(7);
    std::uniform_real_distribution<double> unit(-1, 1);
    std::uniform_int_distribution<int> exponent(-1074, 1000);
    const auto text_of = [&](std::size_t how) -> std::string {
        const double v = unit(gen);
        switch (how % 6) {
            case 0: return fmt::format("{}", v);
            case 1: return fmt::format("{:.18e}", v);  // numpy's savetxt
            case 2: return fmt::format("{}", std::ldexp(v, exponent(gen)));  // subnormal to 1e301
            case 3: return fmt::format("{}", static_cast<int>(v * 1000));
            case 4: return v < 0 ? "-0" : "0.";
            default: return fmt::format("{:.3f}", v).substr(v < 0 ? 0 : 1);  // ".123"
        }
    };
    const std::vector<std::string> names = {"hip", "left knee", "a.b-c_d(1)", "x"};
    for (const std::string header :
         {"time,qw,qx,qy,qz", "qz,QX,frame,qy,qw,time", "time,rx,ry,rz,tx,ty,tz", "sy,time,sx,rx,ry,rz,tx,ty,tz,sz", "track,time,qw,qx,qy,qz",
          "time,e1,e2,e3,track,frame", "frame,m00,m01,m02,m03,m10,m11,m12,m13,m20,m21,m22,m23,m30,m31,m32,m33"}) {
        CAPTURE(header);
        const auto cells = static_cast<std::size_t>(std::count(header.begin(), header.end(), ',')) + 1;
        const auto before_track = std::string_view(header).substr(0, header.find("track"));
        const auto track_at = before_track.size() == header.size()
                                  ? cells
                                  : static_cast<std::size_t>(std::count(before_track.begin(), before_track.end(), ','));
        std::array<std::string, 3> text;  // plain, with blanks, quoted
        text.fill(header + "\n");
        constexpr std::size_t rows = 200;
        for (std::size_t row = 0; row < rows; ++row) {
            for (std::size_t c = 0; c < cells; ++c) {
                const std::string cell = c == track_at ? names[row * names.size() / rows] : text_of(row + c);
                const std::string_view comma = c ? "," : "";
                text[0] += fmt::format("{}{}", comma, cell);
                text[1] += fmt::format("{}{}{}{}", comma, row % 2 ? " " : "\t ", cell, row % 3 ? "" : " \t");
                text[2] += fmt::format("{}\"{}\"", comma, cell);
            }
            for (auto& t : text) t += '\n';
        }
        const auto want = read_keys(text[2], format::csv);
        REQUIRE(want.size() == rows);
        for (const auto& t : {text[0], text[1]}) {
            const auto got = read_keys(t, format::csv);
            REQUIRE(got.size() == want.size());
            for (std::size_t i = 0; i < got.size(); ++i) {
                CAPTURE(i);
                const raw_key &a = got[i].second, &b = want[i].second;
                CHECK(got[i].first == want[i].first);
                CHECK(a.at.line == b.at.line);
                CHECK(a.kind == b.kind);
                CHECK(same_bits(a.time, b.time));
                CHECK(same_bits(a.frame, b.frame));
                CHECK(std::memcmp(a.values.data(), b.values.data(), sizeof a.values) == 0);
                CHECK(a.translation.has_value() == b.translation.has_value());
                if (a.translation) CHECK(std::memcmp(&*a.translation, &*b.translation, sizeof(vec3)) == 0);
                CHECK(a.scale.has_value() == b.scale.has_value());
                if (a.scale) CHECK(std::memcmp(&*a.scale, &*b.scale, sizeof(vec3)) == 0);
            }
        }
    }
}

TEST_CASE("CSV: rows the fast path leaves to cell by cell reading") {
    const std::string header = "time,qw,qx,qy,qz\n";
    const auto value = [&](std::string_view row, std::string_view head = "time,qw,qx,qy,qz\n") {
        return read_keys(std::string(head) + std::string(row), format::csv).at(0).second;
    };
    CHECK(value("0,+1,0,0,0").values[0] == 1);
    CHECK(value("0,\"1\",0,0,0").values[0] == 1);
    CHECK(value("0,1,0,0,0\t ").values[0] == 1);
    const auto error = [&](std::string_view row) { return error_of(header + std::string(row), format::csv); };
    CHECK(error("0,1,0,0,0,0") == "in:2: expected 5 cells as in the header, got 6");
    CHECK(error("0,1,0,0,0,") == "in:2: expected 5 cells as in the header, got 6");
    CHECK(error("0,1,0,0") == "in:2: expected 5 cells as in the header, got 4");
    CHECK(error("0,1,0,,0") == "in:2: column 'qy': expected a finite number, got ''");
    CHECK(error("0,1,0,0,inf") == "in:2: column 'qz': expected a finite number, got 'inf'");
    CHECK(error("0,1,0,0,0x1") == "in:2: column 'qz': expected a finite number, got '0x1'");
    CHECK(error("0,1,0,0,1e") == "in:2: column 'qz': expected a finite number, got '1e'");
    CHECK(error("0,-,0,0,0") == "in:2: column 'qw': expected a finite number, got '-'");
    CHECK(error("0,1,0,0,1e400") == "in:2: column 'qz': expected a finite number, got '1e400'");
    CHECK(error("0;1,0,0,0") == "in:2: expected 5 cells as in the header, got 4");
    CHECK(error("0,1 0,0,0,0") == "in:2: column 'qw': expected a finite number, got '1 0'");
    // Track names the fast path leaves alone: quoted, not ASCII, with '#' or
    // a tab, or empty; and a comment is not a key of track '#'.
    const std::string named = "track,time,qw,qx,qy,qz\n";
    const auto track = [&](std::string_view row) { return read(named + std::string(row), format::csv).tracks.at(0).name; };
    CHECK(track("\"hip\",0,1,0,0,0") == "hip");
    CHECK(track("\"a,b\",0,1,0,0,0") == "a,b");
    CHECK(track("H\xC3\xBC""fte,0,1,0,0,0") == "H\xC3\xBC""fte");
    CHECK(track("a#1,0,1,0,0,0") == "a#1");
    CHECK(track(" hip\t,0,1,0,0,0") == "hip");
    CHECK(read(named + "# hip,0,1,0,0,0\nhip,0,1,0,0,0\n", format::csv).tracks.at(0).keys.at(0).at.line == 3);
    const auto track_error = [&](std::string_view row) { return error_of(named + std::string(row), format::csv); };
    CHECK(track_error(" ,0,1,0,0,0") == "in:2: column 'track': expected a track name, got an empty cell");
    CHECK(track_error("a\tb,0,1,0,0,0") == "in:2: track name 'a\\x09b' has control characters: expected printable text");
    CHECK(track_error("a\xFF,0,1,0,0,0") == "in:2: invalid UTF-8: expected text");
    // An ignored column.
    CHECK(value("0,1,0,0,0,x", "time,qw,qx,qy,qz,note\n").values[0] == 1);
}

TEST_CASE("errors quote bad bytes as \\xNN, a NUL too (what() is a C string)") {
    using namespace std::string_literals;
    CHECK(std::string(error("a\0b\x01\xFF \xC3\xBC"s).what()) == "a\\x00b\\x01\\xff \xC3\xBC");
    CHECK(error_of("time,qw,qx,qy,qz\n0,1,0,0,0\0\n"s, format::csv) ==
          "in:2: column 'qz': expected a finite number, got '0\\x00'");
}

TEST_CASE("CSV: numpy.savetxt's commented header, pandas' unnamed index column") {
    // np.savetxt(f, rows, delimiter=",", header="time,qw,qx,qy,qz")
    const auto k = read_keys("# time,qw,qx,qy,qz\n0.000000000000000000e+00,1,0,0,0\n5.0e-01,0,0,0,1\n", format::csv);
    REQUIRE(k.size() == 2);
    CHECK(k[0].second.at.line == 2);
    CHECK(k[0].second.values[0] == 1);
    CHECK(*k[1].second.time == 0.5);
    CHECK(k[1].second.values[3] == 1);
    CHECK(error_of("# time,qw,qx,qy,qz\n0,half,0,0,0\n", format::csv) ==
          "in:2: column 'qw': expected a finite number, got 'half'");
    CHECK(error_of("# time,qw\n0,1\n", format::csv) == "in:1: missing column 'qx': quat needs qw qx qy qz");
    CHECK(error_of("# exported by hand\n0,1,0,0,0\n", format::csv) ==
          "in:2: expected a header line naming the columns (time or frame, and the rotation's), got a row of numbers");
    const std::string last_comment = "# time,qw,qx,qy,qz\n# exported by hand\n0,1,0,0,0\n";  // the one that counts
    CHECK(error_of(last_comment, format::csv).find("in:3: expected a header line") == 0);
    // A header row after the comment is the header, as it always was.
    CHECK(read_keys("# time,qw,qx,qy,qz\nframe,qw,qx,qy,qz\n3,1,0,0,0\n", format::csv).at(0).second.frame == 3);

    // df.to_csv(f): the index first, under an empty name
    std::ostringstream err;
    warnings warn(err, "in");
    const auto pandas = read_keys(",time,qw,qx,qy,qz,\n0,0.0,1.0,0.0,0.0,0.0,\n", format::csv, warn);
    CHECK(pandas.at(0).second.values[0] == 1);
    CHECK(err.str() == "keyrot: warning: in: ignoring unnamed column 1\n");
}


TEST_CASE("CSV: a spreadsheet's semicolons and decimal commas") {
    // What a spreadsheet in a decimal-comma locale saves as CSV reads as
    // the same keys as the comma-separated file with decimal points.
    const auto semi = read_keys("track;time;ax;ay;az;angle\n\"hip;left\";0,5;0;0;1;90,25\nhip;1.5;0;0;1;-1,5e2\n",
                                format::csv);
    const auto comma = read_keys("track,time,ax,ay,az,angle\nhip;left,0.5,0,0,1,90.25\nhip,1.5,0,0,1,-1.5e2\n",
                                 format::csv);
    REQUIRE(semi.size() == 2);
    REQUIRE(comma.size() == 2);
    for (std::size_t i = 0; i < 2; ++i) {
        CHECK(semi[i].first == comma[i].first);
        CHECK(*semi[i].second.time == *comma[i].second.time);
        CHECK(semi[i].second.values == comma[i].second.values);
    }
    CHECK(semi[0].first == "hip;left");
    CHECK(semi[1].second.values[3] == -150);
    // one decimal mark a number, and a header with commas is comma-separated
    CHECK(error_of("time;qw;qx;qy;qz\n0;1,0,0;0;0;0\n", format::csv) ==
          "in:2: column 'qw': expected a finite number, got '1,0,0'");
    CHECK(error_of("time;qw;qx;qy;qz\n0;1;0;0\n", format::csv) == "in:2: expected 5 cells as in the header, got 4");
    CHECK(error_of("time,qw;qx,qy,qz\n", format::csv).find("in:1: missing column") == 0);
}
