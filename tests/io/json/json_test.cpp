// SPDX-License-Identifier: MIT
// Reading JSON documents and NDJSON lines, whole and streamed.
#include "io/json/json.hpp"
#include "io/open.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <sstream>

#include "helpers.hpp"
#include "io/json/flat_json.hpp"
#include "io/json/json_stream.hpp"
#include "reading.hpp"

using namespace keyrot;
using keyrot::test::error_of;
using keyrot::test::raw_json;
using keyrot::test::read;
using keyrot::test::read_json_keys;

TEST_CASE("JSON: keys, tracks, quaternion order and objects, document fields") {
    const auto doc = read_json_keys(R"({"angles": "radians", "euler": "zyx", "quat_order": "xyzw", "keys": [
        {"time": 0, "quat": [0, 0, 1, 0]},
        {"time": 1, "quat": {"w": 1, "x": 0, "y": 0, "z": 0}},
        {"frame": 48, "axis": [0, 0, 1], "angle": 1.5, "translation": [1, 2, 3]},
        {"time": 3, "rotvec": [0, 1, 0], "scale": [1, 0.5, 2]},
        {"time": 4, "euler": [1, 2, 3]},
        {"time": 5, "matrix": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}]})");
    const auto& t = doc.tracks[0];
    CHECK(t.header.settings.angles == angle_unit::radians);
    CHECK(t.header.settings.euler->name == "zyx");
    CHECK(t.keys[0].values[0] == 0);  // [0, 0, 1, 0] in xyzw: w = 0, z = 1
    CHECK(t.keys[0].values[3] == 1);
    CHECK(t.keys[1].values[0] == 1);
    CHECK(*t.keys[2].frame == 48);
    CHECK(t.keys[2].translation->y == 2);
    CHECK_FALSE(t.keys[2].scale);
    CHECK(t.keys[3].scale->y == 0.5);
    CHECK_FALSE(t.keys[3].translation);
    CHECK(t.keys[5].kind == rep::matrix);
    CHECK(t.keys[3].at.path == "keys[3]");

    const auto tracks = read(R"({"tracks": {"hip": {"keys": [{"time": 0, "quat": [1,0,0,0]}]},
                                            "knee": [{"time": 0, "quat": [1,0,0,0]}]}})",
                             format::json);  // as the commands read it, into tracks
    CHECK(tracks.named);
    CHECK(tracks.tracks.size() == 2);
    CHECK(tracks.tracks[1].name == "knee");
    CHECK(read(R"([{"time": 0, "quat": [1,0,0,0]}])", format::json).tracks[0].keys.size() == 1);
    // keyrot's own output: frames with both frame and time, fps as the key rate
    const auto frames = read(R"({"fps": 30, "frames": [{"frame": 4, "quat": [1,0,0,0]}]})", format::json);
    CHECK(frames.tracks[0].key_fps == 30);
    CHECK(frames.tracks[0].keys[0].time * 30 == 4);
}

TEST_CASE("JSON errors name the key path and what was expected") {
    CHECK(error_of(R"({"tracks": {"hip": {"keys": [{"time": 0, "quat": [1,0,0,0]}, {"time": 1, "quat": [1,0,0]}]}}})",
                   format::json) == "in: tracks.hip.keys[1]: 'quat': expected an array of 4 numbers, got 3 elements");
    CHECK(error_of(R"({"keys": [{"time": "0", "quat": [1,0,0,0]}]})", format::json) ==
          "in: keys[0]: 'time': expected a number, got string \"0\"");
    CHECK(error_of(R"({"keys": [{"time": 0, "quat": [1,0,0,0], "rotvec": [0,0,0]}]})", format::json).find("more than one rotation") !=
          std::string::npos);
    CHECK(error_of(R"({"keys": [{"quat": [1,0,0,0]}]})", format::json) == "in: keys[0]: expected a 'time' or a 'frame'");
    // both, as keyrot's own frames and a table's records have them: the time places the key, the frame labels it
    const key both = read(R"({"keys": [{"time": 0.5, "frame": 7, "quat": [1,0,0,0]}]})", format::json).tracks.at(0).keys.at(0);
    CHECK(both.time == 0.5);
    CHECK(both.frame == 7);
    CHECK(error_of("{\"keys\": [\n{\"time\": 0,", format::json).find("in:2:12: invalid JSON") == 0);
    CHECK(error_of(std::string(100, '[') + std::string(100, ']'), format::json).find("nested deeper") != std::string::npos);
    CHECK(error_of(R"({"keys": [{"time": 0, "matrix": [[1,0,0],[0,1,0]]}]})", format::json).find("expected 3 or 4 rows") !=
          std::string::npos);
    CHECK(error_of(R"({"euler": "XXY", "keys": []})", format::json).find("'euler': expected a sequence") != std::string::npos);
    CHECK(error_of(R"({"tracks": []})", format::json).find("expected an object of named tracks") != std::string::npos);
    CHECK(error_of("42", format::json) == "in: expected a JSON object or array, got number");
}

TEST_CASE("A name twice in one object is refused, naming the object by its path, and its line on one line") {
    const auto twice = [](const char* name) {
        return fmt::format("'{}' appears twice: expected each name once in an object", name);
    };
    CHECK(error_of("{\"tracks\": {\"hip\": {\"keys\": [\n{\"time\": 0, \"quat\": [1,0,0,0]},\n"
                   "{\"time\": 1, \"quat\": {\"w\": 1, \"x\": 0, \"w\": 0}}]}}}",
                   format::json) == "in: tracks.hip.keys[1].quat: " + twice("w"));
    CHECK(error_of("[{\"time\": 0, \"quat\": [1,0,0,0]},\n{\"time\": 1, \"time\": 2, \"quat\": [1,0,0,0]}]",
                   format::json) == "in: [1]: " + twice("time"));
    CHECK(error_of(R"({"tracks": {"a": [], "a": []}})", format::json) == "in:1: tracks: " + twice("a"));
    CHECK(error_of("{\"fps\": 24,\n\"fps\": 30, \"keys\": []}", format::json) == "in: document: " + twice("fps"));
    CHECK(error_of("{\"time\": 0, \"quat\": [1,0,0,0]}\n\n{\"time\": 1, \"time\": 2, \"quat\": [1,0,0,0]}\n",
                   format::ndjson) == "in:3: " + twice("time"));
    CHECK(error_of("{\"time\": 0, \"quat\": [1,0,0,0]}\n{\"time\": 1, \"quat\": {\"w\": 1, \"w\": 1}}\n",
                   format::ndjson) == "in:2: quat: " + twice("w"));
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
    CHECK(field_error(R"({"time": 0, "quat": [1, 0, 0, 0], "scale": [1, 1]})") ==
          "in: keys[0]: 'scale': expected an array of 3 numbers, got 2 elements");
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
    CHECK(error_of("{\"track\": [7], \"time\": 0, \"quat\": [1,0,0,0]}\n", format::ndjson) ==
          "in:1: 'track': expected a string, got array");
}

namespace {

/// Every key of a document (bits of each number, via the shortest
/// round-trip digits) and its track, or the message reading stops with.
std::string dump(const std::string& text) {
    try {
        std::string out;
        for (const auto& [t, keys] : read_json_keys(text).tracks)
            for (const raw_key& k : keys) {
                out += fmt::format("{} {} {} {} {} {} {} {} {} {} [{}]", t.name, t.at.path, static_cast<int>(t.settings.angles),
                                   t.settings.euler ? t.settings.euler->name : "-", t.settings.frame_rate(), k.at.line, k.at.path,
                                   k.time.value_or(-1), k.frame.value_or(-1), static_cast<int>(k.kind),
                                   fmt::join(k.values, " "));
                if (k.translation) out += fmt::format(" {} {} {}", k.translation->x, k.translation->y, k.translation->z);
                if (k.scale) out += fmt::format(" scale {} {} {}", k.scale->x, k.scale->y, k.scale->z);
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
    // member flat_json declines (nested deeper than it reads), which
    // nlohmann-json reads.
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
             // Escapes, decoded: names, a setting, a key's field.
             R"({"tracks": {"caf\u00e9 \ud83e\uddb4 \"q\" \\ \/": [{"time": 0, "quat": [1, 0, 0, 0]}], "\u0061": []}})",
             R"({"\u0065uler": "Z\u0059X", "keys": [{"time": 0, "eul\u0065r": [1, 2, 3], "note": "\b\f\n\r\t"}]})",
             R"({"tracks": {"a": [], "\u0061": []}})",
         }) {
        CAPTURE(doc);
        const std::string note = R"("note": [[[[[[[[[1]]]]]]]]], )";
        const std::string declined = doc.front() == '{' ? "{" + note + doc.substr(1) : "[{" + note + doc.substr(2);
        CHECK(flat.parse(doc) == (doc.find(R"("a": [], "\u0061")") == std::string::npos));  // (declines names twice)
        CHECK(!flat.parse(declined));
        CHECK(dump(doc) == dump(declined));
    }
    // Not blind to a track's own settings; and tracks keep the document's
    // order (the spec's "in input order"), by either parser.
    const std::string two = R"({"tracks": {"b": [{"time": 0, "quat": [1, 0, 0, 0]}], "a": {"fps": 12, "keys": [{"frame": 0, "quat": [1, 0, 0, 0]}]}}})";
    const std::string two_declined = R"({"note": [[[[[[[[[1]]]]]]]]], )" + two.substr(1);
    for (const std::string& order : {dump(two), dump(two_declined)}) {
        CHECK(order.rfind("b ", 0) == 0);
        CHECK(order.find("\na ") != std::string::npos);
        CHECK(order.find(" 12 ") != std::string::npos);
    }
}

namespace {

std::string key_line(const std::string& track, const key_settings& s, const raw_key& k) {
    std::string line = fmt::format("{} {} {} {} {} {} {} {} [{}]", track, static_cast<int>(s.angles),
                                   s.euler ? s.euler->name : "-", s.frame_rate(), k.at.path, k.time.value_or(-1),
                                   k.frame.value_or(-1), static_cast<int>(k.kind), fmt::join(k.values, " "));
    if (k.translation) line += fmt::format(" {} {} {}", k.translation->x, k.translation->y, k.translation->z);
    if (k.scale) line += fmt::format(" scale {} {} {}", k.scale->x, k.scale->y, k.scale->z);
    return line + '\n';
}

/// A JSON document's keys as read_json gives them, with their tracks'
/// names and settings; or its error.
std::string whole_keys(const std::string& text) {
    try {
        const raw_json doc = read_json_keys(text);
        std::string out = doc.named ? "named\n" : "";
        for (const auto& [t, keys] : doc.tracks)
            for (const raw_key& k : keys) out += key_line(t.name, t.settings, k);
        return out;
    } catch (const input_error& e) {
        return e.what();
    }
}

/// The same from the streaming reader (parsed ahead on other threads
/// after the first 1024 keys, where the document has one track); where it
/// declines the document, the keys before and "declined"; where it meets an
/// error, the keys before and "error" (read_json words it).
std::string streamed_keys(const std::string& text, bool ahead = false) {
    std::istringstream in(text);
    std::ostringstream err;
    warnings warn(err, "in");
    read_options o;
    o.source = "in";
    std::string lines, name;
    raw_key k;
    try {
        const auto reader = ahead ? make_key_reader(in, format::json, o, warn, [] { return true; })
                                  : make_key_reader(in, format::json, o, warn);
        while (reader->next(name, k)) lines += key_line(name, reader->settings(), k);
        if (reader->declined()) return lines + "declined";
        return (reader->named() ? "named\n" : "") + lines;
    } catch (const error&) {
        return lines + "error";
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
             // UTF-8 names and strings, as keyrot writes them (a DEL too, which JSON leaves unescaped)
             "{\"tracks\": {\"caf\xc3\xa9\": [" + k + "], \"\xe3\x82\xab\xe3\x83\xa1\xe3\x83\xa9\": [" + k2 +
                 "], \"\xf0\x9f\xa6\xb4\": [" + k + "]}}",
             "[{\"time\": 0, \"quat\": [1, 0, 0, 0], \"note\": \"\xc3\xa9\x7f\"}]",
             R"([{"time": 0, "quat": [1, 0, 0, 0], "note": "}{"}, {"time": 1, "note": "\"", "quat": [0, 1, 0, 0]}])",
             // The same as escapes, as Python's json.dump writes them; and the other escapes
             R"({"tracks": {"caf\u00e9": [)" + k + R"(], "\u30ab\u30e1\u30e9": [)" + k2 + R"(], "\ud83e\uddb4": [)" + k + "]}}",
             R"({"note": "\"}\\\/\b\f\n\r\t\u00E9", "\u0066ps": 30, "k\u0065ys": [{"time": 0, "quat": [1, 0, 0, 0], "note": "\"]}"}]})",
             R"({"tracks": {"\"a\\\"": [)" + k + "]}}",
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
             "\xEF\xBB\xBF[" + k + "]", R"({"note": [[[[[[[[[[1]]]]]]]]]], "keys": [)" + k + "]}",
             R"({"tracks": {"a": [)" + k + R"(], "\u0061": [)" + k + "]}}", "42", "\"keys\"", "",
             // Escapes nlohmann-json refuses: a lone surrogate either way, one not followed by its pair, unknown, cut short.
             R"({"tracks": {"\ud83e": [)" + k + "]}}", R"({"tracks": {"\uddb4": [)" + k + "]}}",
             R"({"tracks": {"\ud83e\u0041": [)" + k + "]}}", R"({"tracks": {"\x": [)" + k + "]}}",
             R"({"tracks": {"\u00e": [)" + k + "]}}", R"([{"time": 0, "quat": [1, 0, 0, 0], "note": "\ud800"}])",
             R"([{"time": 0, "quat": [1, 0, 0, 0], "note": "\q"}])",
             // What is not UTF-8 (overlong, a surrogate, cut short, past U+10FFFF): read_json words it.
             "{\"tracks\": {\"\xc0\xaf\": [" + k + "]}}", "{\"tracks\": {\"\xed\xa0\x80\": [" + k + "]}}",
             "{\"tracks\": {\"\xc3\": [" + k + "]}}", "{\"tracks\": {\"\xf4\x90\x80\x80\": [" + k + "]}}",
             "[{\"time\": 0, \"quat\": [1, 0, 0, 0], \"note\": \"\xe3\x82\"}]",
             "[" + k + "]\n" + std::string(1, '\0') + "x", "[" + k + "]" + std::string(1, '\0'),
             // A bare array's keys that name their tracks, a table's records: grouped by track, as a whole.
             R"([{"track": "a", "time": 0, "quat": [1, 0, 0, 0]}])",
         }) {
        CAPTURE(doc);
        CHECK(streamed_keys(doc).ends_with("declined"));
    }
    // Errors in the keys it reads: thrown, for read_json to word (after the keys before them).
    CHECK(streamed_keys(R"({"tracks": {"a\u0001": [)" + k + "]}}") == "error");
    CHECK(streamed_keys(R"({"keys": [{"time": 0, "quat": [1, 0, 0]}]})") == "error");
    CHECK(streamed_keys("[" + k + ", " + k2 + ", 7]") == streamed_keys("[" + k + ", " + k2 + "]") + "error");
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
    // ... and of escapes, in a name and in a value.
    for (std::size_t pad = 65480; pad < 65540; ++pad) {
        const std::string doc = "{" + std::string(pad, ' ') + R"("tracks": {"\"\u00e9\\": {"note": "\"]}\\\"", "keys": [)" + keys + "]}}}";
        CAPTURE(pad);
        const std::string streamed = streamed_keys(doc);
        CHECK(streamed.find("\n\"\xc3\xa9\\ 0 - 24 tracks.\"\xc3\xa9\\.keys[1399] 1399 -1 0 [") != std::string::npos);
        CHECK(streamed == whole_keys(doc));
    }
    // Parsed ahead, each track's keys keep its settings and names.
    const std::string two = R"({"tracks": {"a": {"quat_order": "xyzw", "keys": [)" + keys +
                            R"(]}, "b": {"angles": "radians", "fps": 30, "keys": [)" + keys + "]}}}";
    CHECK(streamed_keys(two, true).find("\nb 1 - 30 tracks.b.keys[1399] 1399 ") != std::string::npos);
    CHECK(streamed_keys(two, true) == whole_keys(two));
    // Parsed ahead, an error still comes after the keys before it (the
    // document is then read whole, to say what is wrong), and so does a
    // key flat_json declines.
    const std::string bad = "[" + keys + R"(, {"time": 1400, "quat": [1, 0, 0]}])";
    CHECK(streamed_keys(bad, true) == streamed_keys("[" + keys + "]") + "error");
    const std::string escaped = "[" + keys + R"(, {"time": 1400, "quat": [1, 0, 0, 0], "note": [[[[[[[[[1]]]]]]]]]}])";
    CHECK(streamed_keys(escaped, true) == streamed_keys("[" + keys + "]") + "declined");
    CHECK(streamed_keys(escaped) == streamed_keys("[" + keys + "]") + "declined");
    CHECK(whole_keys(bad) == "in: [1400]: 'quat': expected an array of 4 numbers, got 3 elements");
}

TEST_CASE("JSON: a bare array of records that name their tracks, as pandas writes a table's rows") {
    // interleaved rows of two tracks, as a CSV table of them may be: each track's keys in order,
    // the tracks in the order they first appear, each key named by its place in the array
    const document doc = read(R"([{"track": "knee", "time": 0, "qw": 1, "qx": 0, "qy": 0, "qz": 0},
        {"track": "hip", "time": 0, "qw": 1, "qx": 0, "qy": 0, "qz": 0},
        {"track": "knee", "time": 0.5, "qw": 0, "qx": 1, "qy": 0, "qz": 0, "note": 3},
        {"track": 7, "time": 0.5, "quat": [0, 0, 1, 0]}])",
                              format::json);
    CHECK(doc.named);
    REQUIRE(doc.tracks.size() == 3);
    CHECK(doc.tracks[0].name == "knee");
    CHECK(doc.tracks[1].name == "hip");
    CHECK(doc.tracks[2].name == "7");
    REQUIRE(doc.tracks[0].keys.size() == 2);
    CHECK(doc.tracks[0].keys[1].at.path == "[2]");
    CHECK(doc.tracks[0].keys[1].rotation.x == 1);
    CHECK(error_of(R"([{"track": "a", "time": 0, "quat": [1, 0, 0, 0]}, {"time": 1, "quat": [1, 0, 0, 0]}])", format::json) ==
          "in: [1]: some keys have a 'track' and some do not: expected all or none");
    CHECK(error_of(R"([{"track": "a", "time": 1, "qw": 1, "qx": 0, "qy": 0, "qz": 0},
        {"track": "b", "time": 0, "qw": 1, "qx": 0, "qy": 0, "qz": 0}, {"track": "a", "time": 0, "qw": 1, "qx": 0, "qy": 0, "qz": 0}])",
                   format::json) == "in: [2]: time 0 s is not after the previous key's 1 s: expected strictly increasing times");
}

TEST_CASE("NDJSON: lines flat_json takes give the keys and messages nlohmann-json's reading gives") {
    // Each line twice: as written, which flat_json takes, and with a member
    // flat_json declines (nested deeper than it reads), which nlohmann-json reads.
    const auto dump_lines = [](const std::string& text) {
        try {
            std::string out;
            for (const auto& [name, k] : keyrot::test::read_keys(text, format::ndjson))
                out += fmt::format("{} {} {} {} {} [{}] {} {}\n", name, k.at.line, k.time.value_or(-1), k.frame.value_or(-1),
                                   static_cast<int>(k.kind), fmt::join(k.values, " "),
                                   k.translation ? fmt::format("{} {} {}", k.translation->x, k.translation->y, k.translation->z) : "",
                                   k.scale ? fmt::format("{} {} {}", k.scale->x, k.scale->y, k.scale->z) : "");
            return out;
        } catch (const input_error& e) {
            return std::string(e.what());
        }
    };
    flat_json line;
    for (const std::string key : {
             R"("time": 0.5, "quat": [0.5, -0.5, 0.5, -0.5])", R"("frame": 3, "time": -0, "quat": {"w": 1, "x": 0, "y": -0, "z": 0})",
             R"("time": 1e-3, "axis": [0, 0, 1], "angle": 90, "translation": [1, -2.5, 3e2])",
             R"("time": 1, "quat": [1, 0, 0, 0], "scale": [0.5, 2, -1e-3])",
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
             R"("track": "a\tb", "time": 0, "quat": [1, 0, 0, 0])", R"("track": "caf\u00e9\ud83e\uddb4", "time": 0, "quat": [1, 0, 0, 0])",
             R"("tr\u0061ck": "\"hip\"", "t\u0069me": 0, "quat": [1, 0, 0, 0])",
             R"("time": 0.5, "frame": 12, "qw": 1, "qx": 0, "QY": 0, "qz": 0)",
             R"("track": 3, "time": 0.5, "ax": "0", "ay": 0, "az": 1, "angle_rad": 1, "tx": "", "ty": null, "tz": "")",
             R"("time": 0.5, "rx": 1, "ry": 2, "rz": "x")", R"("time": 0.5, "e1": 1, "e2": 2)",
         }) {
        CAPTURE(key);
        const std::string taken = "{" + key + "}", declined = R"({"note": [[[[[[[[[1]]]]]]]]], )" + key + "}";
        CHECK(line.parse(taken));
        CHECK(!line.parse(declined));
        CHECK(dump_lines(taken + "\n") == dump_lines(declined + "\n"));
        CHECK(dump_lines("\n" + declined + "\n" + taken + "\n") == dump_lines("\n" + taken + "\n" + declined + "\n"));
    }
    // The dump is not blind: the two lines differ when a number does.
    CHECK(dump_lines(R"({"time": 0, "quat": [1, 0, 0, 0]})") != dump_lines(R"({"time": 0, "quat": [1, -0.0, 0, 0]})"));
}

