// SPDX-License-Identifier: MIT
// open_table: the rows of a large output, formatted on other threads and
// written in chunks, are the bytes the writer gives on one thread.
#include "io/open.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "helpers.hpp"
#include "reading.hpp"

using namespace keyrot;

namespace {

/// Tracks of `rows` frames each, with and without translations and scales.
std::vector<std::vector<sample>> tracks_of(std::size_t count, std::size_t rows) {
    std::vector<std::vector<sample>> tracks(count);
    for (std::size_t t = 0; t < count; ++t)
        for (std::size_t i = 0; i < rows; ++i) {
            const double a = 0.001 * static_cast<double>(i + t);
            std::optional<vec3> translation, scale;
            if (t % 2 == 0) translation = vec3{a, -a, 1};
            if (t % 3 == 0) scale = vec3{1 + a, 1, 1 - a};
            tracks[t].push_back({static_cast<double>(i) / 24, static_cast<double>(i),
                                 quat{std::cos(a), 0, 0, std::sin(a)}, translation, scale});
        }
    return tracks;
}

/// Track t's row for sample s: track 1's rows (of rotations alone) without
/// a frame, as convert writes keys that gave only a time.
table_row as_row(const sample& s, std::size_t t) {
    table_row r{s};
    if (t == 1) r.frame.reset();
    return r;
}

/// The table written by one writer on this thread, the reference.
std::string direct(format f, const table_info& info, const write_options& w, const std::vector<std::vector<sample>>& tracks) {
    std::string out;
    std::ostringstream err;
    warnings warn(err, "in");
    const auto writer = test::make_writer(f, out, info, w, warn);
    for (std::size_t t = 0; t < tracks.size(); ++t) {
        writer->begin_track("track " + std::to_string(t), channels{tracks[t].front().translation.has_value(), tracks[t].front().scale.has_value()});
        for (const sample& s : tracks[t]) writer->row(as_row(s, t));
    }
    writer->finish();
    return out;
}

std::string through_table(format f, const std::optional<std::string>& path, const table_info& info,
                          const write_options& w, const std::vector<std::vector<sample>>& tracks) {
    std::ostringstream out, err;
    warnings warn(err, "in");
    const auto table = open_table(f, path, out, info, w, warn);
    for (std::size_t t = 0; t < tracks.size(); ++t) {
        table->begin_track("track " + std::to_string(t), channels{tracks[t].front().translation.has_value(), tracks[t].front().scale.has_value()}, track_interpolation{});
        // Every other row as a frame (as resample gives them), which the
        // table may pass on in fewer bytes than a row.
        for (std::size_t i = 0; i < tracks[t].size(); ++i) {
            if (i % 2 == 0 && t != 1) table->frame(tracks[t][i]);
            else table->row(as_row(tracks[t][i], t));
        }
    }
    table->finish();
    return out.str();
}

}  // namespace

TEST_CASE("open_table: the same bytes as the writer alone, small or large, to a stream or a file") {
    table_info info;
    info.named = true;
    info.carried = {true, true};
    info.fps = 24;
    write_options w;
    w.representation = rep::quat;
    const keyrot::test::scratch s;
    // 10 rows stay on this thread; 4 x 50,000 rows cross batches, tracks
    // begin inside batches, and the output passes several chunks.
    for (const std::size_t rows : {std::size_t{10}, std::size_t{50000}}) {
        const auto tracks = tracks_of(4, rows);
        for (const format f : {format::csv, format::json, format::ndjson}) {
            CAPTURE(rows);
            CAPTURE(to_string(f));
            const std::string want = direct(f, info, w, tracks);
            CHECK(through_table(f, std::nullopt, info, w, tracks) == want);
            const std::string path = (s.dir / "out").string();
            CHECK(through_table(f, path, info, w, tracks).empty());
            CHECK(s.read(path) == want);
        }
    }
}

TEST_CASE("open_table: a table never finished leaves no file, and its file is not touched") {
    const keyrot::test::scratch s;
    const std::string path = s.file("out.csv", "before\n");
    {
        std::ostringstream out, err;
        warnings warn(err, "in");
        const auto table = open_table(format::csv, path, out, table_info{}, write_options{}, warn);
        table->begin_track("", channels{}, track_interpolation{});
        const auto tracks = tracks_of(2, 50000);
        for (const sample& row : tracks[1]) table->row(table_row{row});  // (track 1: no translations)
    }  // an error before finish(): the table goes
    CHECK(s.read(path) == "before\n");
    CHECK(std::distance(std::filesystem::directory_iterator(s.dir), {}) == 1);
}
