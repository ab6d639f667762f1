// Readers and writers of CSV, JSON and NDJSON.
#include "io/io.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <sstream>
#include <thread>

#include "helpers.hpp"
#include "fast/flat_json.hpp"

using namespace keyrot;

namespace {

raw_document read(std::string_view text, format f, quat_order order = quat_order::wxyz) {
    std::ostringstream err;
    warnings warn(err, "in");
    read_options o;
    o.source = "in";
    o.order = order;
    return read_document(text, f, o, warn);
}

std::string error_of(std::string_view text, format f) {
    try {
        read(text, f);
    } catch (const input_error& e) {
        return e.what();
    }
    return "";
}

std::string write(format f, const table_info& info, const write_options& w, const std::vector<sample>& rows,
                  const std::string& track = "") {
    std::string out;
    std::ostringstream err;
    warnings warn(err, "in");
    auto writer = make_writer(f, out, info, w, warn);
    writer->begin_track(track, rows.front().translation.has_value());
    for (const sample& s : rows) writer->row(s);
    writer->finish();
    return out;
}

}  // namespace

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
}

TEST_CASE("CSV: columns in any order and case, comments, blank lines, BOM, CRLF") {
    const auto doc = read("\xEF\xBB\xBF# comment\r\n\r\n QZ , Time,qx,QW,qy\r\n1,0,0,0,0\r\n  # another\n0,1,0,1,0", format::csv);
    REQUIRE(doc.tracks.size() == 1);
    CHECK_FALSE(doc.named);
    const auto& k = doc.tracks[0].keys;
    REQUIRE(k.size() == 2);
    CHECK(*k[0].time == 0);
    CHECK(k[0].values[0] == 0);  // w
    CHECK(k[0].values[3] == 1);  // z
    CHECK(k[1].values[0] == 1);
    CHECK(k[1].at.line == 6);
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

TEST_CASE("CSV: every representation's columns") {
    CHECK(read("time,ax,ay,az,angle\n0,0,0,1,90\n", format::csv).tracks[0].keys[0].kind == rep::axis_angle);
    CHECK(read("time,e1,e2,e3\n0,1,2,3\n", format::csv).tracks[0].keys[0].kind == rep::euler);
    const auto m = read("frame,m00,m01,m02,m10,m11,m12,m20,m21,m22\n5,1,0,0,0,1,0,0,0,1\n", format::csv);
    CHECK(m.tracks[0].keys[0].kind == rep::matrix);
    CHECK(*m.tracks[0].keys[0].frame == 5);
    const auto m4 = read("time,m00,m01,m02,m03,m10,m11,m12,m13,m20,m21,m22,m23,m30,m31,m32,m33\n"
                         "0,1,0,0,4,0,1,0,5,0,0,1,6,0,0,0,1\n",
                         format::csv);
    CHECK(m4.tracks[0].keys[0].kind == rep::matrix4);
    CHECK(m4.tracks[0].keys[0].values[3] == 4);
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
          "in:1: expected commas between the columns, got 'time\\x09qw\\x09qx\\x09qy\\x09qz'");
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
         {"time,qw,qx,qy,qz", "qz,QX,frame,qy,qw,time", "time,rx,ry,rz,tx,ty,tz", "track,time,qw,qx,qy,qz",
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
        const auto want = read(text[2], format::csv);
        REQUIRE(want.tracks.size() == (track_at < cells ? names.size() : 1));
        for (const auto& t : {text[0], text[1]}) {
            const auto got = read(t, format::csv);
            REQUIRE(got.tracks.size() == want.tracks.size());
            for (std::size_t n = 0; n < got.tracks.size(); ++n) {
                const auto& a = got.tracks[n].keys;
                const auto& b = want.tracks[n].keys;
                CHECK(got.tracks[n].name == want.tracks[n].name);
                REQUIRE(a.size() == b.size());
                for (std::size_t i = 0; i < a.size(); ++i) {
                    CAPTURE(i);
                    CHECK(a[i].at.line == b[i].at.line);
                    CHECK(a[i].kind == b[i].kind);
                    CHECK(same_bits(a[i].time, b[i].time));
                    CHECK(same_bits(a[i].frame, b[i].frame));
                    CHECK(std::memcmp(a[i].values.data(), b[i].values.data(), sizeof a[i].values) == 0);
                    CHECK(a[i].translation.has_value() == b[i].translation.has_value());
                    if (a[i].translation) CHECK(std::memcmp(&*a[i].translation, &*b[i].translation, sizeof(vec3)) == 0);
                }
            }
        }
    }
}

TEST_CASE("CSV: rows the fast path leaves to cell by cell reading") {
    const std::string header = "time,qw,qx,qy,qz\n";
    const auto value = [&](std::string_view row) { return read(header + std::string(row), format::csv).tracks[0].keys[0]; };
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
    std::ostringstream err;
    warnings warn(err, "in");
    read_options o;
    o.source = "in";
    CHECK(read_document("time,qw,qx,qy,qz,note\n0,1,0,0,0,x\n", format::csv, o, warn).tracks[0].keys[0].values[0] == 1);
}

TEST_CASE("errors quote bad bytes as \\xNN, a NUL too (what() is a C string)") {
    using namespace std::string_literals;
    CHECK(std::string(error("a\0b\x01\xFF \xC3\xBC"s).what()) == "a\\x00b\\x01\\xff \xC3\xBC");
    CHECK(error_of("time,qw,qx,qy,qz\n0,1,0,0,0\0\n"s, format::csv) ==
          "in:2: column 'qz': expected a finite number, got '0\\x00'");
}

TEST_CASE("CSV: numpy.savetxt's commented header, pandas' unnamed index column") {
    // np.savetxt(f, rows, delimiter=",", header="time,qw,qx,qy,qz")
    const auto doc = read("# time,qw,qx,qy,qz\n0.000000000000000000e+00,1,0,0,0\n5.0e-01,0,0,0,1\n", format::csv);
    REQUIRE(doc.tracks.size() == 1);
    const auto& k = doc.tracks[0].keys;
    REQUIRE(k.size() == 2);
    CHECK(k[0].at.line == 2);
    CHECK(k[0].values[0] == 1);
    CHECK(*k[1].time == 0.5);
    CHECK(k[1].values[3] == 1);
    CHECK(error_of("# time,qw,qx,qy,qz\n0,half,0,0,0\n", format::csv) ==
          "in:2: column 'qw': expected a finite number, got 'half'");
    CHECK(error_of("# time,qw\n0,1\n", format::csv) == "in:1: missing column 'qx': quat needs qw qx qy qz");
    CHECK(error_of("# exported by hand\n0,1,0,0,0\n", format::csv) ==
          "in:2: expected a header line naming the columns (time or frame, and the rotation's), got a row of numbers");
    const std::string last_comment = "# time,qw,qx,qy,qz\n# exported by hand\n0,1,0,0,0\n";  // the one that counts
    CHECK(error_of(last_comment, format::csv).find("in:3: expected a header line") == 0);
    // A header row after the comment is the header, as it always was.
    CHECK(read("# time,qw,qx,qy,qz\nframe,qw,qx,qy,qz\n3,1,0,0,0\n", format::csv).tracks[0].keys[0].frame == 3);

    // df.to_csv(f): the index first, under an empty name
    std::ostringstream err;
    warnings warn(err, "in");
    read_options o;
    o.source = "in";
    const auto pandas = read_document(",time,qw,qx,qy,qz,\n0,0.0,1.0,0.0,0.0,0.0,\n", format::csv, o, warn);
    CHECK(pandas.tracks[0].keys[0].values[0] == 1);
    CHECK(err.str() == "keyrot: warning: in: ignoring unnamed column 1\n");
}

TEST_CASE("JSON: keys, tracks, quaternion order and objects, document fields") {
    const auto doc = read(R"({"angles": "radians", "euler": "zyx", "quat_order": "xyzw", "keys": [
        {"time": 0, "quat": [0, 0, 1, 0]},
        {"time": 1, "quat": {"w": 1, "x": 0, "y": 0, "z": 0}},
        {"frame": 48, "axis": [0, 0, 1], "angle": 1.5, "translation": [1, 2, 3]},
        {"time": 3, "rotvec": [0, 1, 0]},
        {"time": 4, "euler": [1, 2, 3]},
        {"time": 5, "matrix": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}]})",
                          format::json);
    const auto& t = doc.tracks[0];
    CHECK(t.settings.angles == angle_unit::radians);
    CHECK(t.settings.euler->name == "zyx");
    CHECK(t.keys[0].values[0] == 0);  // [0, 0, 1, 0] in xyzw: w = 0, z = 1
    CHECK(t.keys[0].values[3] == 1);
    CHECK(t.keys[1].values[0] == 1);
    CHECK(*t.keys[2].frame == 48);
    CHECK(t.keys[2].translation->y == 2);
    CHECK(t.keys[5].kind == rep::matrix);
    CHECK(t.keys[3].at.path == "keys[3]");

    const auto tracks = read(R"({"tracks": {"hip": {"keys": [{"time": 0, "quat": [1,0,0,0]}]},
                                            "knee": [{"time": 0, "quat": [1,0,0,0]}]}})",
                             format::json);
    CHECK(tracks.named);
    CHECK(tracks.tracks.size() == 2);
    CHECK(tracks.tracks[1].name == "knee");
    CHECK(read(R"([{"time": 0, "quat": [1,0,0,0]}])", format::json).tracks[0].keys.size() == 1);
    // keyrot's own output: frames with both frame and time, fps as the key rate
    const auto frames = read(R"({"fps": 30, "frames": [{"frame": 3, "time": 0.1, "quat": [1,0,0,0]}]})", format::json);
    CHECK(frames.tracks[0].settings.key_fps == 30);
}

TEST_CASE("JSON errors name the key path and what was expected") {
    CHECK(error_of(R"({"tracks": {"hip": {"keys": [{"time": 0, "quat": [1,0,0,0]}, {"time": 1, "quat": [1,0,0]}]}}})",
                   format::json) == "in: tracks.hip.keys[1]: 'quat': expected an array of 4 numbers, got 3 elements");
    CHECK(error_of(R"({"keys": [{"time": "0", "quat": [1,0,0,0]}]})", format::json) ==
          "in: keys[0]: 'time': expected a number, got string \"0\"");
    CHECK(error_of(R"({"keys": [{"time": 0, "quat": [1,0,0,0], "rotvec": [0,0,0]}]})", format::json).find("more than one rotation") !=
          std::string::npos);
    CHECK(error_of(R"({"keys": [{"time": 0, "frame": 0, "quat": [1,0,0,0]}]})", format::json) ==
          "in: keys[0]: a key has both 'time' and 'frame': expected exactly one");
    CHECK(error_of(R"({"keys": [{"quat": [1,0,0,0]}]})", format::json) == "in: keys[0]: expected a 'time' or a 'frame'");
    CHECK(error_of("{\"keys\": [\n{\"time\": 0,", format::json).find("in:2:12: invalid JSON") == 0);
    CHECK(error_of(std::string(100, '[') + std::string(100, ']'), format::json).find("nested deeper") != std::string::npos);
    CHECK(error_of(R"({"keys": [{"time": 0, "matrix": [[1,0,0],[0,1,0]]}]})", format::json).find("expected 3 or 4 rows") !=
          std::string::npos);
    CHECK(error_of(R"({"euler": "XXY", "keys": []})", format::json).find("'euler': expected a sequence") != std::string::npos);
    CHECK(error_of(R"({"tracks": []})", format::json).find("expected an object of named tracks") != std::string::npos);
    CHECK(error_of("42", format::json) == "in: expected a JSON object or array, got number");
}

TEST_CASE("JSON errors name the field down to the element, as a JSON path") {
    const auto field_error = [](const std::string& key) {
        return error_of(R"({"keys": [)" + key + "]}", format::json);
    };
    CHECK(field_error(R"({"time": 0, "quat": [1, 0, "x", 0]})") == "in: keys[0]: 'quat[2]': expected a number, got string \"x\"");
    CHECK(field_error(R"({"time": 0, "quat": {"w": 1, "x": 0, "y": null, "z": 0}})") ==
          "in: keys[0]: 'quat.y': expected a number, got null");
    CHECK(field_error(R"({"time": 0, "quat": {"w": 1, "x": 0, "z": 0}})") ==
          "in: keys[0]: 'quat' object: missing 'y': expected w x y z");
    CHECK(field_error(R"({"time": 0, "axis": [0, 0, true], "angle": 90})") ==
          "in: keys[0]: 'axis[2]': expected a number, got boolean");
    CHECK(field_error(R"({"time": 0, "axis": [0, 0, 1], "angle": "90"})") ==
          "in: keys[0]: 'angle': expected a number, got string \"90\"");
    CHECK(field_error(R"({"time": 0, "rotvec": [0, [0], 0]})") == "in: keys[0]: 'rotvec[1]': expected a number, got array");
    CHECK(field_error(R"({"time": 0, "euler": [{}, 0, 0]})") == "in: keys[0]: 'euler[0]': expected a number, got object");
    CHECK(field_error(R"({"time": 0, "matrix": [[1, 0, 0], [0, 1, "0"], [0, 0, 1]]})") ==
          "in: keys[0]: 'matrix[1][2]': expected a number, got string \"0\"");
    CHECK(field_error(R"({"time": 0, "matrix": [[1, 0, 0], [0, 1], [0, 0, 1]]})") ==
          "in: keys[0]: 'matrix[1]': expected an array of 3 numbers, got 2 elements");
    CHECK(field_error(R"({"time": 0, "quat": [1, 0, 0, 0], "translation": [0, "1", 2]})") ==
          "in: keys[0]: 'translation[1]': expected a number, got string \"1\"");
    CHECK(field_error(R"({"frame": "3", "quat": [1, 0, 0, 0]})") == "in: keys[0]: 'frame': expected a number, got string \"3\"");
}

TEST_CASE("NDJSON: one key per line, tracks by field, errors by line") {
    const auto doc = read("{\"track\": \"a\", \"time\": 0, \"quat\": [1,0,0,0]}\n\n"
                          "{\"track\": \"b\", \"time\": 0, \"rotvec\": [0,0,1]}\n",
                          format::ndjson);
    CHECK(doc.named);
    CHECK(doc.tracks.size() == 2);
    CHECK(doc.tracks[1].keys[0].at.line == 3);
    CHECK(error_of("{\"time\": 0, \"quat\": [1,0,0,0]}\n{\"time\": 1}\n", format::ndjson).find("in:2: no rotation") == 0);
    CHECK(error_of("{\"time\": 0, \"quat\": [1,0,0,0]}\n{oops\n", format::ndjson).find("in:2:2: invalid JSON") == 0);
    CHECK(error_of("{\"time\": 0, \"quat\": [1,0,0,0]}\n\n{\"time\": 1, \"quat\": [1,0,0,\"0\"]}\n", format::ndjson) ==
          "in:3: 'quat[3]': expected a number, got string \"0\"");
    CHECK(error_of("{\"track\": \"a\", \"time\": 0, \"quat\": [1,0,0,0]}\n{\"time\": 1, \"quat\": [1,0,0,0]}\n",
                   format::ndjson) == "in:2: some lines have a 'track' and some do not: expected all or none");
    CHECK(error_of("{\"track\": 7, \"time\": 0, \"quat\": [1,0,0,0]}\n", format::ndjson) ==
          "in:1: 'track': expected a string, got number");
}

namespace {

/// Every key of a document (bits of each number, via the shortest
/// round-trip digits) and its track, or the message reading stops with.
std::string dump(const std::string& text, format f) {
    try {
        std::string out;
        for (const auto& t : read(text, f).tracks)
            for (const raw_key& k : t.keys) {
                out += fmt::format("{} {} {} {} {} {} {} {} {} {} [{}]", t.name, t.at.path, static_cast<int>(t.settings.angles),
                                   t.settings.euler ? t.settings.euler->name : "-", t.settings.key_fps, k.at.line, k.at.path,
                                   k.time.value_or(-1), k.frame.value_or(-1), static_cast<int>(k.kind),
                                   fmt::join(k.values, " "));
                if (k.translation) out += fmt::format(" {} {} {}", k.translation->x, k.translation->y, k.translation->z);
                out += '\n';
            }
        return out;
    } catch (const input_error& e) {
        return std::string(e.what());
    }
}

}  // namespace

TEST_CASE("JSON: documents flat_json takes give the keys and messages nlohmann-json's reading gives") {
    // Each document twice: as written, which flat_json takes, and with a
    // member flat_json declines (an escaped string), which nlohmann-json reads.
    flat_json flat;
    for (const std::string doc : {
             R"({"keys": [{"time": 0, "quat": [1, 0, 0, 0]}, {"time": 1, "rotvec": [0, 0, 1.5], "translation": [1, 2, 3]}]})",
             R"({"fps": 30, "frames": [{"frame": 0, "time": -0, "euler": [10, 20, 30]}, {"frame": 3, "euler": [0, 0, 0]}],
                 "euler": "ZYX", "angles": "radians", "quat_order": "xyzw"})",
             R"({"quat_order": "xyzw", "keys": [{"time": 0, "quat": [0, 0, 0, 1]}, {"time": 1, "quat": {"w": 1, "x": 0, "y": 0, "z": 0}}]})",
             R"({"angles": "radians", "tracks": {"zeta": {"keys": [{"time": 0, "axis": [0, 0, 1], "angle": 1}]},
                 "alpha": {"angles": "degrees", "fps": 12, "frames": [{"frame": 1, "matrix": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}]},
                 "mid": [{"time": 2, "matrix": [[1, 0, 0, 4], [0, 1, 0, 5], [0, 0, 1, 6], [0, 0, 0, 1]]}]}})",
             R"([{"time": 0, "quat": [1, 0, 0, 0]}, {"time": 5e-1, "quat": [0, 1, 0, 0]}])",
             R"({"tracks": {"a": {"keys": [{"time": 0, "quat": [1, 0, "x", 0]}]}}})",
             R"({"tracks": {"b": {"keys": []}, "a": {"keys": 5}}})", R"({"tracks": {}})", R"({"tracks": []})",
             R"({"tracks": {"a\u0001": {"keys": []}}})", R"({"keys": [], "frames": []})", R"({"other": 1})",
             R"({"angles": "grads", "keys": []})", R"({"euler": "XXY", "keys": []})", R"({"euler": 5, "keys": []})",
             R"({"quat_order": "wzyx", "keys": []})", R"({"fps": 0, "keys": []})", R"({"fps": "24", "keys": []})",
             R"({"keys": [{"time": 0, "frame": 0, "quat": [1, 0, 0, 0]}]})", R"({"keys": [{"quat": [1, 0, 0, 0]}]})",
             R"({"keys": [{"time": 0, "matrix": [[1, 0, 0], [0, 1, 0]]}]})", R"({"keys": [7]})", R"({"keys": [null]})",
         }) {
        CAPTURE(doc);
        const std::string declined = doc.front() == '{' ? "{\"note\": \"\\u00e9\", " + doc.substr(1)
                                                        : "[{\"note\": \"\\u00e9\", " + doc.substr(2);
        CHECK(flat.parse(doc) == (doc.find('\\') == std::string::npos));
        CHECK(!flat.parse(declined));
        CHECK(dump(doc, format::json) == dump(declined, format::json));
    }
    // Not blind to a track's own settings; and tracks keep the document's
    // order (the spec's "in input order"), by either parser.
    const std::string two = R"({"tracks": {"b": [{"time": 0, "quat": [1, 0, 0, 0]}], "a": {"fps": 12, "keys": [{"frame": 0, "quat": [1, 0, 0, 0]}]}}})";
    const std::string two_declined = R"({"note": "\u00e9", )" + two.substr(1);
    for (const std::string& order : {dump(two, format::json), dump(two_declined, format::json)}) {
        CHECK(order.rfind("b ", 0) == 0);
        CHECK(order.find("\na ") != std::string::npos);
        CHECK(order.find(" 12 ") != std::string::npos);
    }
}

namespace {

std::string key_line(const std::string& track, const key_settings& s, const raw_key& k) {
    std::string line = fmt::format("{} {} {} {} {} {} {} {} [{}]", track, static_cast<int>(s.angles),
                                   s.euler ? s.euler->name : "-", s.key_fps, k.at.path, k.time.value_or(-1),
                                   k.frame.value_or(-1), static_cast<int>(k.kind), fmt::join(k.values, " "));
    if (k.translation) line += fmt::format(" {} {} {}", k.translation->x, k.translation->y, k.translation->z);
    return line + '\n';
}

/// A JSON document's keys as read_json gives them, with their tracks'
/// names and settings; or its error.
std::string whole_keys(const std::string& text) {
    try {
        const raw_document doc = read(text, format::json);
        std::string out = doc.named ? "named\n" : "";
        for (const raw_track& t : doc.tracks)
            for (const raw_key& k : t.keys) out += key_line(t.name, t.settings, k);
        return out;
    } catch (const input_error& e) {
        return e.what();
    }
}

/// The same from the streaming reader (parsed ahead on other threads
/// after the first 1024 keys, where the document has one track); where it
/// throws, the keys before and "declined".
std::string streamed_keys(const std::string& text, bool ahead = false) {
    std::istringstream in(text);
    std::ostringstream err;
    warnings warn(err, "in");
    read_options o;
    o.source = "in";
    std::string lines, name;
    raw_key k;
    try {
        auto reader = make_key_reader(in, format::json, o, warn);
        if (ahead) reader = read_ahead(std::move(reader), [] { return true; });
        while (reader->next(name, k)) lines += key_line(name, reader->settings(), k);
        return (reader->named() ? "named\n" : "") + lines;
    } catch (const error&) {
        return lines + "declined";
    }
}

}  // namespace

TEST_CASE("JSON streamed: the keys read_json gives, or declined for read_json to read whole") {
    const std::string k = R"({"time": 0, "quat": [1, 0, 0, 0]})", k2 = R"({"time": 1, "quat": [0, 1, 0, 0]})";
    // Settings before keys, as keyrot writes: streamed, in every shape.
    for (const std::string& doc : std::vector<std::string>{
             R"({"angles": "radians", "euler": "zyx", "quat_order": "xyzw", "keys": [
                 {"time": 0, "quat": [0, 0, 1, 0]}, {"time": 1, "quat": {"w": 1, "x": 0, "y": 0, "z": 0}},
                 {"frame": 48, "axis": [0, 0, 1], "angle": 1.5, "translation": [1, 2, 3]}, {"time": 3, "rotvec": [0, 1, 0]},
                 {"time": 4, "euler": [1, 2, 3]}, {"time": 5, "matrix": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}]})",
             R"({"fps": 30, "method": "slerp", "rep": "quat", "frames": [{"frame": 3, "time": 0.1, "quat": [1, 0, 0, 0]},
                 {"frame": 4, "time": -0, "quat": [1e-3, 1E+2, -0, 0.5]}]})",
             R"({"angles": "radians", "tracks": {"zeta": {"keys": [{"time": 0, "axis": [0, 0, 1], "angle": 1}]},
                 "alpha": {"angles": "degrees", "fps": 12, "frames": [{"frame": 1, "matrix": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}]},
                 "mid": [{"time": 2, "matrix": [[1, 0, 0, 4], [0, 1, 0, 5], [0, 0, 1, 6], [0, 0, 0, 1]]}]}})",
             "[" + k + ",\r\n\t" + k2 + "]", " \n[ " + k + " ] \n",
             R"({"note": {"a": [1, 2, {"b": null}], "c": "x,]} "}, "keys": [)" + k + "], \"after\": [true, false, \"{[\"]}",
             R"({"quat_order": "xyzw", "tracks": {"a": {"quat_order": "wxyz", "tracks": 5, "keys": [)" + k + "]}, \"b\": [" + k2 +
                 "], \"\": [" + k + "]}}",
         }) {
        CAPTURE(doc);
        const std::string streamed = streamed_keys(doc);
        CHECK(streamed == whole_keys(doc));
    }
    // What read_json reads only once it has the whole text, reads otherwise
    // than a walk in order would, or reports as an error: declined.
    for (const std::string& doc : std::vector<std::string>{
             R"({"keys": [)" + k + R"(], "angles": "radians"})", R"({"tracks": {"a": [)" + k + R"(]}, "fps": 12})",
             R"({"tracks": {"a": {"keys": [)" + k + R"(], "euler": "xyz"}}})", R"({"keys": [)" + k + R"(], "tracks": {"a": [)" + k + "]}}",
             R"({"tracks": {"a": [)" + k + R"(]}, "keys": [)" + k + "]}", R"({"keys": [)" + k + R"(], "frames": [)" + k + "]}",
             R"({"keys": [)" + k + R"(], "keys": [)" + k + "]}", R"({"tracks": {"a": [)" + k + R"(], "a": [)" + k + "]}}",
             R"({"keys": []})", R"({"tracks": {}})", R"({"tracks": {"a": {"fps": 2}}})", R"({"other": 1})", R"({"keys": 5})",
             R"({"keys": [)" + k + "]} x", R"({"keys": [)" + k, R"({"keys": [)" + k + ",]}", R"({"keys": [)" + k + " " + k2 + "]}",
             "\xEF\xBB\xBF[" + k + "]", R"({"note": "\u00e9", "keys": [)" + k + "]}", R"({"tracks": {"\u00e9": [)" + k + "]}}",
             R"({"note": [[[[[[[[[[1]]]]]]]]]], "keys": [)" + k + "]}", R"({"keys": [{"time": 0, "quat": [1, 0, 0]}]})",
             R"({"tracks": {"a\u0001": [)" + k + "]}}", "42", "\"keys\"", "", "[" + k + ", " + k2 + ", 7]",
             "[" + k + "]\n" + std::string(1, '\0') + "x", "[" + k + "]" + std::string(1, '\0'),
         }) {
        CAPTURE(doc);
        CHECK(streamed_keys(doc).ends_with("declined"));
    }
    // Read in blocks of 64 KB: a block ends in each place of a setting, and of a key.
    std::string keys;
    for (int i = 0; i < 1400; ++i)
        keys += fmt::format("{}{{\"time\": {}, \"quat\": [{}, 0.25, -0.5, 1e-3]}}", i ? ",\n " : "", i, i * 0.1);
    for (std::size_t pad = 65500; pad < 65560; ++pad) {
        const std::string doc = "{" + std::string(pad, ' ') + R"("quat_order": "xyzw", "keys": [)" + keys + "]}";
        CAPTURE(pad);
        const std::string streamed = streamed_keys(doc);
        CHECK(streamed.find("\n 0 - 24 keys[1399] 1399 -1 0 [") != std::string::npos);
        CHECK(streamed == whole_keys(doc));
        if (pad % 20 == 0) CHECK(streamed_keys(doc, true) == streamed);
    }
    // Parsed ahead, each track's keys keep its settings and names.
    const std::string two = R"({"tracks": {"a": {"quat_order": "xyzw", "keys": [)" + keys +
                            R"(]}, "b": {"angles": "radians", "fps": 30, "keys": [)" + keys + "]}}}";
    CHECK(streamed_keys(two, true).find("\nb 1 - 30 tracks.b.keys[1399] 1399 ") != std::string::npos);
    CHECK(streamed_keys(two, true) == whole_keys(two));
    // Parsed ahead, an error still comes after the keys before it (the
    // document is then read whole, to say what is wrong).
    const std::string bad = "[" + keys + R"(, {"time": 1400, "quat": [1, 0, 0]}])";
    CHECK(streamed_keys(bad, true) == streamed_keys("[" + keys + "]") + "declined");
    CHECK(whole_keys(bad) == "in: [1400]: 'quat': expected an array of 4 numbers, got 3 elements");
}

TEST_CASE("NDJSON: lines flat_json takes give the keys and messages nlohmann-json's reading gives") {
    // Each line twice: as written, which flat_json takes, and with a member
    // flat_json declines (an escaped string), which nlohmann-json reads.
    const auto dump_lines = [](const std::string& text) { return dump(text, format::ndjson); };
    flat_json line;
    for (const std::string key : {
             R"("time": 0.5, "quat": [0.5, -0.5, 0.5, -0.5])", R"("frame": 3, "time": -0, "quat": {"w": 1, "x": 0, "y": -0, "z": 0})",
             R"("time": 1e-3, "axis": [0, 0, 1], "angle": 90, "translation": [1, -2.5, 3e2])",
             R"("time": 2, "rotvec": [0.1, 0.2, 0.3])", R"("time": 2, "euler": [10, 20, 30])",
             R"("time": 2, "matrix": [[1, 0, 0], [0, 1, 0], [0, 0, 1]])",
             R"("time": 2, "matrix": [[1, 0, 0, 5], [0, 1, 0, 6], [0, 0, 1, 7], [0, 0, 0, 1]])",
             R"("time": 0, "quat": [1, 0, "x", 0])", R"("time": 0, "quat": {"w": 1, "x": 0, "y": null, "z": 0})",
             R"("time": 0, "quat": {"w": 1, "x": 0, "z": 0})", R"("time": 0, "axis": [0, 0, true], "angle": 90)",
             R"("time": 0, "axis": [0, 0, 1], "angle": "90")", R"("time": 0, "axis": [0, 0, 1])", R"("time": 0, "angle": 9)",
             R"("time": 0, "rotvec": [0, [0], 0])", R"("time": 0, "euler": [{}, 0, 0])",
             R"("time": 0, "matrix": [[1, 0, 0], [0, 1, "0"], [0, 0, 1]])", R"("time": 0, "matrix": [[1, 0, 0], [0, 1], [0, 0, 1]])",
             R"("time": 0, "matrix": 5)", R"("time": 0, "matrix": [[1]])", R"("time": 0, "quat": [1, 0, 0, 0], "translation": [0, "1", 2])",
             R"("frame": "3", "quat": [1, 0, 0, 0])", R"("quat": [1, 0, 0, 0])", R"("time": 0, "quat": [1, 0, 0, 0], "rotvec": [0, 0, 0])",
             R"("time": 0)", R"("time": 0, "quat": [1, 0, 0])", R"("time": "0", "quat": [1, 0, 0, 0])",
             R"("track": "hip", "time": 0, "quat": [1, 0, 0, 0])", R"("track": 7, "time": 0, "quat": [1, 0, 0, 0])",
             R"("track": "a\tb", "time": 0, "quat": [1, 0, 0, 0])",
         }) {
        CAPTURE(key);
        const std::string taken = "{" + key + "}", declined = "{\"note\": \"\\u00e9\", " + key + "}";
        CHECK(line.parse(taken) == (key.find('\\') == std::string::npos));
        CHECK(!line.parse(declined));
        CHECK(dump_lines(taken + "\n") == dump_lines(declined + "\n"));
        CHECK(dump_lines("\n" + declined + "\n" + taken + "\n") == dump_lines("\n" + taken + "\n" + declined + "\n"));
    }
    // The dump is not blind: the two lines differ when a number does.
    CHECK(dump_lines(R"({"time": 0, "quat": [1, 0, 0, 0]})") != dump_lines(R"({"time": 0, "quat": [1, -0.0, 0, 0]})"));
}

namespace {

/// Every key a reader gives, and the message it stops with ("" at the end).
struct reading_result {
    std::vector<std::pair<std::string, raw_key>> keys;
    std::string error;
};

reading_result read_all(key_reader& reader, std::size_t at_most = SIZE_MAX) {
    reading_result r;
    std::string name;
    raw_key k;
    try {
        while (r.keys.size() < at_most && reader.next(name, k)) r.keys.emplace_back(name, k);
    } catch (const input_error& e) {
        r.error = e.what();
    }
    return r;
}

/// A track of `n` keys, key i on line i + 2 (the track's name changes
/// halfway, to one too long to be stored in place), with a bad number on
/// line `bad_line`, if any. NDJSON's first line is a blank one.
std::string numbered_keys(std::size_t n, std::size_t bad_line = 0, format f = format::csv) {
    std::string text = f == format::csv ? "track,time,qw,qx,qy,qz\n" : "\n";
    for (std::size_t i = 0; i < n; ++i) {
        const std::string name = i < n / 2 ? "a" : "a track with a long name";
        const std::string qz = i + 2 == bad_line ? (f == format::csv ? "x" : "\"x\"") : std::to_string(i);
        text += f == format::csv ? fmt::format("{},{},1,0,0,{}\n", name, i, qz)
                                 : fmt::format("{{\"track\": \"{}\", \"time\": {}, \"quat\": [1, 0, 0, {}]}}\n", name, i, qz);
    }
    return text;
}

}  // namespace

TEST_CASE("read_ahead: the same keys and errors as the reader it wraps, in order") {
    // Both are parsed on two threads, a batch each in turn.
    for (const format f : {format::csv, format::ndjson}) {
        CAPTURE(f == format::csv);
        std::ostringstream err;
        warnings warn(err, "in");
        read_options o;
        o.source = "in";
        const auto read = [&](const std::string& text, bool ahead, int& asked, std::size_t at_most = SIZE_MAX) {
            std::istringstream in(text);
            auto reader = make_key_reader(in, f, o, warn);
            if (ahead) reader = read_ahead(std::move(reader), [&asked] { return ++asked > 0; });
            return read_all(*reader, at_most);
        };
        const auto same = [](const reading_result& a, const reading_result& b) {
            REQUIRE(a.keys.size() == b.keys.size());
            for (std::size_t i = 0; i < a.keys.size(); ++i) {
                CAPTURE(i);
                CHECK(a.keys[i].first == b.keys[i].first);
                CHECK(a.keys[i].second.at.line == b.keys[i].second.at.line);
                CHECK(a.keys[i].second.time == b.keys[i].second.time);
                CHECK(a.keys[i].second.values == b.keys[i].second.values);
            }
            CHECK(a.error == b.error);
        };
        int asked = 0;
        // Keys and line numbers straight from the text: key i is on line i + 2.
        const reading_result plain = read(numbered_keys(5000, 0, f), false, asked);
        REQUIRE(plain.keys.size() == 5000);
        CHECK(plain.keys[4999].second.at.line == 5001);
        CHECK(plain.keys[4999].second.values[3] == 4999);
        CHECK(plain.keys[4999].first == "a track with a long name");
        CHECK(plain.error.empty());
        same(read(numbered_keys(5000, 0, f), true, asked), plain);
        CHECK(asked == 1);

        // The error after the keys before it, whether in the threads' first
        // batch, a later one, or among the keys read before they start.
        for (const std::size_t bad : std::initializer_list<std::size_t>{3000, 1025, 1026, 2050, 5001, 500}) {
            CAPTURE(bad);
            const reading_result expected = read(numbered_keys(5000, bad, f), false, asked);
            CHECK(expected.keys.size() == bad - 2);
            CHECK(expected.error == (f == format::csv
                                         ? fmt::format("in:{}: column 'qz': expected a finite number, got 'x'", bad)
                                         : fmt::format("in:{}: 'quat[3]': expected a number, got string \"x\"", bad)));
            same(read(numbered_keys(5000, bad, f), true, asked), expected);
        }

        // Batches of no keys (a run of blank lines) and keys after them.
        std::string gaps = numbered_keys(3000, 0, f);
        const auto key_1200 = gaps.find(f == format::csv ? "\na,1200," : "\n{\"track\": \"a\", \"time\": 1200,");
        REQUIRE(key_1200 != std::string::npos);
        gaps.insert(key_1200 + 1, std::string(5000, '\n'));
        const reading_result with_gaps = read(gaps, false, asked);
        REQUIRE(with_gaps.keys.size() == 3000);
        CHECK(with_gaps.keys[1199].second.at.line == 1201);
        CHECK(with_gaps.keys[1200].second.at.line == 6202);
        same(read(gaps, true, asked), with_gaps);

        // A small input never asks; a caller that stops early (the threads
        // a few batches ahead, waiting) ends without hanging.
        asked = 0;
        same(read(numbered_keys(1000, 0, f), true, asked), read(numbered_keys(1000, 0, f), false, asked));
        CHECK(asked == 0);
        const reading_result first = read(numbered_keys(20000, 0, f), true, asked, 1500);
        CHECK(first.keys.size() == 1500);
        CHECK(first.keys[1499].second.values[3] == 1499);
        CHECK(asked == 1);

        // Not worth it: all on the caller's thread, the same again.
        std::istringstream in(numbered_keys(3000, 2500, f));
        const auto no_thread = read_ahead(make_key_reader(in, f, o, warn), [&asked] { return ++asked < 0; });
        same(read_all(*no_thread), read(numbered_keys(3000, 2500, f), false, asked));
        CHECK(asked == 2);
    }

    // NDJSON's lines name their tracks all or none, as the first key says:
    // a line that breaks the rule is found, and worded, as on the caller's
    // thread, also first in a thread's first batch (lines 1025 and 2049,
    // the keys before them read on the caller's thread).
    for (const std::size_t change : std::initializer_list<std::size_t>{1025, 2049, 3000}) {
        for (const bool named_first : {true, false}) {
            CAPTURE(change);
            CAPTURE(named_first);
            std::string text;
            for (std::size_t i = 0; i < 5000; ++i) {  // key i on line i + 1
                const bool named = (i + 1 < change) == named_first;
                text += fmt::format("{{{}\"time\": {}, \"quat\": [1, 0, 0, {}]}}\n", named ? "\"track\": \"a\", " : "", i, i);
            }
            std::ostringstream err;
            warnings warn(err, "in");
            read_options o;
            o.source = "in";
            const auto read = [&](bool ahead) {
                std::istringstream in(text);
                auto reader = make_key_reader(in, format::ndjson, o, warn);
                if (ahead) reader = read_ahead(std::move(reader), [] { return true; });
                return read_all(*reader);
            };
            const reading_result alone = read(false), ahead = read(true);
            CHECK(alone.keys.size() == change - 1);
            CHECK(alone.error ==
                  fmt::format("in:{}: some lines have a 'track' and some do not: expected all or none", change));
            CHECK(ahead.keys.size() == alone.keys.size());
            CHECK(ahead.error == alone.error);
        }
    }

    // numpy's commented header: its first key is read with the header, and
    // comes out first.
    std::string numpy = "# time,qw,qx,qy,qz\n";
    for (int i = 0; i < 3000; ++i) numpy += fmt::format("{}.0e+00,1,0,0,{}\n", i, i);
    std::ostringstream err;
    warnings warn(err, "in");
    read_options o;
    o.source = "in";
    std::istringstream in(numpy);
    const auto ahead = read_ahead(make_key_reader(in, format::csv, o, warn), [] { return true; });
    const reading_result all = read_all(*ahead);
    REQUIRE(all.keys.size() == 3000);
    for (std::size_t i = 0; i < all.keys.size(); ++i) {
        CAPTURE(i);
        CHECK(all.keys[i].second.at.line == i + 2);
        CHECK(all.keys[i].second.values[3] == static_cast<double>(i));
    }
}

TEST_CASE("read_ahead: a reader without a line parser is read on the caller's thread") {
    // NDJSON has a parser only once its first key has said whether lines
    // name their tracks; read_ahead starts no threads without one.
    std::ostringstream err;
    warnings warn(err, "in");
    read_options o;
    std::istringstream in("\n{\"time\": 0, \"quat\": [1, 0, 0, 0]}\n");
    const auto ndjson = make_key_reader(in, format::ndjson, o, warn);
    CHECK(ndjson->parser() == nullptr);
    std::string name;
    raw_key k;
    REQUIRE(ndjson->next(name, k));
    CHECK(ndjson->parser() != nullptr);
    CHECK_FALSE(ndjson->named());

    struct counting_reader final : key_reader {
        std::size_t count = 0;
        bool elsewhere = false;  // next() called on another thread
        std::thread::id caller = std::this_thread::get_id();
        bool next(std::string&, raw_key& key) override {
            elsewhere = elsewhere || std::this_thread::get_id() != caller;
            key.time = static_cast<double>(count);
            return count++ < 5000;
        }
        bool named() const override { return false; }
        location start() const override { return {}; }
        const key_settings& settings() const override { return defaults; }
        key_settings defaults;
    };
    auto inner = std::make_unique<counting_reader>();
    const counting_reader& counted = *inner;
    int asked = 0;
    const auto reader = read_ahead(std::move(inner), [&asked] { return ++asked > 0; });
    const reading_result all = read_all(*reader);
    REQUIRE(all.keys.size() == 5000);
    CHECK(all.keys[4999].second.time == 4999);
    CHECK(asked == 1);
    CHECK_FALSE(counted.elsewhere);
}

TEST_CASE("writers: CSV, JSON and NDJSON tables") {
    const double s = std::sqrt(0.5);
    const std::vector<sample> rows = {{0, 0.0, quat{}, vec3{1, 2, 3}}, {0.5, 12.0, quat{s, 0, 0, s}, vec3{0, 0, -1}}};
    table_info info;
    info.translation = true;
    info.fps = 24;
    info.method = "slerp";
    write_options w;
    w.representation = rep::quat;
    w.precision = 4;
    // --precision rounds the values, not the times
    CHECK(write(format::csv, info, w, rows) ==
          "# keyrot {\"fps\": 24, \"method\": \"slerp\", \"rep\": \"quat\", \"angles\": \"degrees\", \"quat_order\": \"wxyz\"}\n"
          "frame,time,qw,qx,qy,qz,tx,ty,tz\n0,0,1,0,0,0,1,2,3\n12,0.5,0.7071,0,0,0.7071,0,0,-1\n");
    CHECK(write(format::json, info, w, rows) ==
          "{\"fps\": 24, \"method\": \"slerp\", \"rep\": \"quat\", \"angles\": \"degrees\", \"quat_order\": \"wxyz\", "
          "\"frames\": [\n"
          "{\"frame\": 0, \"time\": 0, \"quat\": [1, 0, 0, 0], \"translation\": [1, 2, 3]},\n"
          "{\"frame\": 12, \"time\": 0.5, \"quat\": [0.7071, 0, 0, 0.7071], \"translation\": [0, 0, -1]}]}\n");
    info.named = true;
    w.representation = rep::axis_angle;
    CHECK(write(format::ndjson, info, w, rows, "hip") ==
          "{\"fps\": 24, \"method\": \"slerp\", \"rep\": \"axis-angle\", \"angles\": \"degrees\"}\n"
          "{\"track\": \"hip\", \"frame\": 0, \"time\": 0, \"axis\": [1, 0, 0], \"angle\": 0, \"translation\": [1, 2, 3]}\n"
          "{\"track\": \"hip\", \"frame\": 12, \"time\": 0.5, \"axis\": [0, 0, 1], \"angle\": 90, \"translation\": [0, 0, -1]}\n");
    CHECK(write(format::csv, info, w, rows, "a,b").find("\"a,b\",0,0,1,0,0,0,1,2,3\n") != std::string::npos);
}

TEST_CASE("keyrot reads what it writes, in every format and representation") {
    keyrot::test::random_rotations rng(77);
    std::vector<sample> rows;
    for (int i = 0; i < 5; ++i) rows.push_back({i / 24.0, static_cast<double>(i), rng.next(), vec3{0.5 * i, 1, 2}});
    table_info info;
    info.translation = true;
    info.fps = 24;
    for (format f : {format::csv, format::json, format::ndjson}) {
        for (const auto& named : names_of<rep>) {
            write_options w;
            w.representation = named.value;
            w.euler = parse_euler_seq("yxz");
            CAPTURE(to_string(f));
            CAPTURE(named.name);
            const std::string text = write(f, info, w, rows);
            std::ostringstream err;
            warnings warn(err, "in");
            read_options o;
            o.source = "in";
            o.settings.euler = w.euler;
            const raw_document doc = read_document(text, f, o, warn);
            const track t = make_track(doc.tracks[0], warn);
            REQUIRE(t.keys.size() == rows.size());
            for (std::size_t i = 0; i < rows.size(); ++i) {
                CHECK(keyrot::test::same_rotation(t.keys[i].rotation, rows[i].rotation, 1e-15));
                CHECK(t.keys[i].time == rows[i].time);
                CHECK(std::fabs(t.keys[i].translation->x - rows[i].translation->x) <= 1e-15);
            }
        }
    }
}
