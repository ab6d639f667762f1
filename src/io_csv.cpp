#include "keyrot/io_csv.hpp"

#include <fmt/format.h>

#include <algorithm>


namespace keyrot {
namespace {

constexpr std::array<std::string_view, 7> matrix4_only = {"m03", "m13", "m23", "m30", "m31", "m32", "m33"};

/// Splits one line into cells; "..." quotes a cell, "" inside is a quote.
std::vector<std::string> split_cells(std::string_view line, const std::string& where) {
    std::vector<std::string> cells(1);
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c != '"') cells.back() += c;
            else if (i + 1 < line.size() && line[i + 1] == '"') cells.back() += '"', ++i;
            else quoted = false;
        } else if (c == ',') {
            cells.emplace_back();
        } else if (c == '"') {
            quoted = true;
        } else {
            cells.back() += c;
        }
    }
    if (quoted) throw input_error(where, "unterminated quoted cell: expected a closing '\"'");
    return cells;
}

/// Where each known column is, resolved once from the header.
struct columns {
    std::size_t count = 0;
    std::optional<std::size_t> track, time, frame;
    rep kind = rep::quat;
    std::vector<std::size_t> rotation;  // in (w, x, y, z) order for quaternions
    std::optional<std::array<std::size_t, 3>> translation;
};

std::string column_list(rep r) {
    const auto cols = rotation_columns(r, quat_order::wxyz);
    if (r == rep::matrix || r == rep::matrix4) return fmt::format("{}..{}", cols.front(), cols.back());
    return fmt::format("{}", fmt::join(cols, " "));
}

columns parse_header(const std::vector<std::string>& cells, const std::string& where, warnings& warn) {
    columns cols;
    cols.count = cells.size();
    std::map<std::string, std::size_t> index;
    for (std::size_t i = 0; i < cells.size(); ++i) {
        const std::string name = ascii_lower(trim(cells[i]));
        if (name.empty()) throw input_error(where, fmt::format("column {} has no name: expected a column name", i + 1));
        if (!index.emplace(name, i).second)
            throw input_error(where, fmt::format("column '{}' appears twice: expected each column once", name));
    }
    auto find = [&index](std::string_view name) -> std::optional<std::size_t> {
        const auto it = index.find(std::string(name));
        if (it == index.end()) return std::nullopt;
        return it->second;
    };
    std::vector<bool> known(cells.size(), false);
    auto claim = [&](std::string_view name) {
        auto at = find(name);
        if (at) known[*at] = true;
        return at;
    };
    cols.track = claim("track");
    cols.time = claim("time");
    cols.frame = claim("frame");
    if (!cols.time && !cols.frame) throw input_error(where, "no time column: expected a 'time' or 'frame' column");

    // The representation: the one whose columns appear. The 3x3 matrix
    // columns are also part of the 4x4 ones, so matrix4 is chosen by the
    // columns only it has.
    const bool four = std::any_of(matrix4_only.begin(), matrix4_only.end(), [&](auto n) { return find(n).has_value(); });
    std::optional<rep> found;
    for (rep r : {rep::quat, rep::axis_angle, rep::rotvec, rep::euler, four ? rep::matrix4 : rep::matrix}) {
        const auto names = rotation_columns(r, quat_order::wxyz);
        if (std::none_of(names.begin(), names.end(), [&](auto n) { return find(n).has_value(); })) continue;
        if (found)
            throw input_error(where, fmt::format("columns of two rotation representations ({} and {}): expected one",
                                                 to_string(*found), to_string(r)));
        for (auto n : names)
            if (!find(n))
                throw input_error(where, fmt::format("missing column '{}': {} needs {}", n, to_string(r), column_list(r)));
        found = r;
        for (auto n : names) cols.rotation.push_back(*claim(n));
    }
    if (!found)
        throw input_error(where, fmt::format("no rotation columns: expected {}, {}, {}, {} or {}", column_list(rep::quat),
                                             column_list(rep::axis_angle), column_list(rep::rotvec),
                                             column_list(rep::euler), column_list(rep::matrix)));
    cols.kind = *found;

    const auto tx = claim("tx"), ty = claim("ty"), tz = claim("tz");
    if (tx || ty || tz) {
        if (!(tx && ty && tz)) throw input_error(where, "translation needs all of the columns tx ty tz");
        if (cols.kind == rep::matrix4)
            throw input_error(where, "4x4 matrix and tx ty tz columns: expected one translation per key");
        cols.translation = std::array<std::size_t, 3>{*tx, *ty, *tz};
    }
    for (std::size_t i = 0; i < cells.size(); ++i)
        if (!known[i]) warn.once("column", fmt::format("ignoring unknown column '{}'", trim(cells[i])));
    return cols;
}

double number_cell(const std::vector<std::string>& cells, std::size_t at, std::string_view name,
                   const std::string& where) {
    if (auto v = parse_number(cells[at])) return *v;
    throw input_error(where, fmt::format("column '{}': expected a finite number, got '{}'", name,
                                         trim(cells[at]).substr(0, 40)));
}

bool empty_cell(const std::vector<std::string>& cells, std::size_t at) { return trim(cells[at]).empty(); }

}  // namespace

raw_document read_csv(std::string_view text, const read_options& opts, warnings& warn) {
    track_collector tracks(opts.settings);
    std::optional<columns> cols;
    std::string header_where;
    line_reader lines(text);
    std::string_view line;
    while (lines.next(line)) {
        const std::string_view content = trim(line);
        if (content.empty() || content.front() == '#') continue;
        const std::string where = fmt::format("{}:{}", opts.source, lines.number());
        if (!is_valid_utf8(line)) throw input_error(where, "invalid UTF-8: expected text");
        const auto cells = split_cells(line, where);
        if (!cols) {
            header_where = where;
            cols = parse_header(cells, where, warn);
            tracks.document().named = cols->track.has_value();
            continue;
        }
        if (cells.size() != cols->count)
            throw input_error(where, fmt::format("expected {} cells as in the header, got {}", cols->count, cells.size()));

        raw_key k;
        k.where = where;
        k.kind = cols->kind;
        if (cols->time && !(cols->frame && empty_cell(cells, *cols->time)))
            k.time = number_cell(cells, *cols->time, "time", where);
        if (cols->frame && !(cols->time && empty_cell(cells, *cols->frame)))
            k.frame = number_cell(cells, *cols->frame, "frame", where);
        if (!k.time && !k.frame) throw input_error(where, "no time: expected a 'time' or a 'frame'");
        const auto names = rotation_columns(cols->kind, quat_order::wxyz);
        for (std::size_t i = 0; i < cols->rotation.size(); ++i)
            k.values[i] = number_cell(cells, cols->rotation[i], names[i], where);
        if (cols->translation) {
            const auto& t = *cols->translation;
            const int empty = empty_cell(cells, t[0]) + empty_cell(cells, t[1]) + empty_cell(cells, t[2]);
            if (empty == 0)
                k.translation = vec3{number_cell(cells, t[0], "tx", where), number_cell(cells, t[1], "ty", where),
                                     number_cell(cells, t[2], "tz", where)};
            else if (empty != 3)
                throw input_error(where, "columns tx ty tz: expected three numbers or three empty cells");
        }

        std::string name;
        if (cols->track) {
            name = std::string(trim(cells[*cols->track]));
            if (name.empty()) throw input_error(where, "column 'track': expected a track name, got an empty cell");
        }
        tracks.add(name, std::move(k));
    }
    if (!cols) throw input_error(opts.source, "empty input: expected a CSV header and keys");
    if (tracks.document().tracks.empty()) throw input_error(header_where, "header only: expected at least one key");
    return std::move(tracks.document());
}

namespace {

void append_cell_text(std::string& out, std::string_view text) {
    if (text.find_first_of(",\"\r\n") == std::string_view::npos && trim(text) == text) {
        out += text;
        return;
    }
    out += '"';
    for (char c : text) {
        if (c == '"') out += '"';
        out += c;
    }
    out += '"';
}

class csv_writer final : public table_writer {
public:
    csv_writer(std::string& out, const table_info& info, const write_options& opts, warnings& warn)
        : out_(out), info_(info), opts_(opts), warn_(warn) {
        frame_ = info.times == time_columns::frame_and_time || (info.times == time_columns::as_given && info.all_frames);
        time_ = info.times != time_columns::as_given || !info.all_frames || info.any_time;
        translation_ = info.translation && opts.representation != rep::matrix4;
        std::vector<std::string_view> header;
        if (info.named) header.push_back("track");
        if (frame_) header.push_back("frame");
        if (time_) header.push_back(info.time_name);
        for (auto c : rotation_columns(opts.representation, opts.order)) header.push_back(c);
        if (translation_)
            for (auto c : translation_columns) header.push_back(c);
        fmt::format_to(std::back_inserter(out_), "{}\n", fmt::join(header, ","));
    }

    void begin_track(const std::string& name, bool) override { name_ = name; }

    void row(const sample& s) override {
        if (info_.named) append_cell_text(out_, name_), out_ += ',';
        if (frame_) append_number(out_, *s.frame, std::nullopt), out_ += ',';
        if (time_) append_number(out_, s.time, opts_.precision), out_ += ',';
        const rotation_values r = row_values(s, opts_, warn_);
        for (std::size_t i = 0; i < r.size; ++i) {
            if (i) out_ += ',';
            append_number(out_, r.v[i], opts_.precision);
        }
        if (translation_) {
            if (s.translation) {
                for (double t : {s.translation->x, s.translation->y, s.translation->z})
                    out_ += ',', append_number(out_, t, opts_.precision);
            } else {
                out_ += ",,,";
            }
        }
        out_ += '\n';
    }

    void finish() override {}

private:
    std::string& out_;
    table_info info_;
    write_options opts_;
    warnings& warn_;
    std::string name_;
    bool frame_ = false, time_ = false, translation_ = false;
};

}  // namespace

std::unique_ptr<table_writer> make_csv_writer(std::string& out, const table_info& info, const write_options& opts,
                                              warnings& warn) {
    return std::make_unique<csv_writer>(out, info, opts, warn);
}

}  // namespace keyrot
