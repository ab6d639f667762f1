#include "io/csv/csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <deque>
#include <map>
#include <optional>
#include <utility>

#include "ground/text.hpp"
#include "io/common/line_reader.hpp"
#include "io/json/flat_json.hpp"
#include "io/json/json_keys.hpp"

namespace keyrot {
namespace {

constexpr std::array<std::string_view, 7> matrix4_only = {"m03", "m13", "m23", "m30", "m31", "m32", "m33"};

/// The cells of one line, as views into the line (or, for a line with
/// quotes, into unquoted copies). "..." quotes a cell, "" inside is a quote.
class cell_splitter {
public:
    /// `separator`: ',', or ';' for the CSV of a spreadsheet whose locale
    /// writes decimal commas.
    explicit cell_splitter(char separator = ',') : separator_(separator) {}

    const std::vector<std::string_view>& split(std::string_view line, const std::string& source, std::size_t line_no) {
        cells_.clear();
        has_quotes_.clear();
        if (line.find('"') == std::string_view::npos) {  // the common case: no copies
            std::size_t start = 0;
            for (std::size_t comma; (comma = line.find(separator_, start)) != std::string_view::npos; start = comma + 1)
                cells_.push_back(line.substr(start, comma - start));
            cells_.push_back(line.substr(start));
            return cells_;
        }
        quoted_.clear();
        quoted_.emplace_back();
        has_quotes_.assign(1, false);
        bool quoted = false;
        for (std::size_t i = 0; i < line.size(); ++i) {
            const char c = line[i];
            if (quoted) {
                if (c != '"') quoted_.back() += c;
                else if (i + 1 < line.size() && line[i + 1] == '"') quoted_.back() += '"', ++i;
                else quoted = false;
            } else if (c == separator_) {
                quoted_.emplace_back();
                has_quotes_.push_back(false);
            } else if (c == '"') {
                // Spaces before the quote are the cell's padding, not its text.
                if (trim(quoted_.back()).empty()) quoted_.back().clear();
                quoted = true;
                has_quotes_.back() = true;
            } else if (!(has_quotes_.back() && (c == ' ' || c == '\t'))) {  // (nor spaces after it)
                quoted_.back() += c;
            }
        }
        if (quoted)
            throw input_error(where(source, line_no), "unterminated quoted cell: expected a closing '\"'");
        for (const std::string& cell : quoted_) cells_.emplace_back(cell);
        return cells_;
    }

    /// Cell i of the last line split as it is meant: a quoted cell's text
    /// exactly, any other trimmed.
    std::string_view text(std::size_t i) const {
        return i < has_quotes_.size() && has_quotes_[i] ? cells_[i] : trim(cells_[i]);
    }

private:
    char separator_;
    std::vector<std::string_view> cells_;
    std::deque<std::string> quoted_;  // stable addresses for the views
    std::vector<bool> has_quotes_;    // for a line with quotes: which cells had them
};

/// Rows of at most this many cells may be read by the fast path.
constexpr std::size_t max_plain_cells = 24;

/// Where each known column is, resolved once from the header.
struct columns {
    /// ',' or ';': a semicolon-separated table, whose numbers may have a
    /// decimal comma (what a spreadsheet saves as CSV in many locales).
    char separator = ',';
    std::size_t count = 0;
    bool plain = false;  // no ignored columns, at most max_plain_cells: rows for csv_rows::read_plain
    std::optional<std::size_t> track, time, frame;
    rep kind = rep::quat;
    std::vector<std::size_t> rotation;  // in (w, x, y, z) order for quaternions
    std::optional<std::array<std::size_t, 3>> translation, scale;
    std::vector<std::size_t> weights;  // w0, w1, ...
    std::optional<std::array<std::size_t, 3>> velocity, acceleration;
};

std::string column_list(rep r) {
    const auto cols = rotation_columns(r, quat_order::wxyz);
    if (r == rep::matrix || r == rep::matrix4) return fmt::format("{}..{}", cols.front(), cols.back());
    return fmt::format("{}", fmt::join(cols, " "));
}

/// The separator of a table whose header is `line`: ';' where the header
/// has semicolons and no commas (no column name keyrot reads has either).
char separator_of(std::string_view header) {
    return header.find(';') != std::string_view::npos && header.find(',') == std::string_view::npos ? ';' : ',';
}

/// A number with a decimal point, or in a semicolon-separated table a
/// decimal comma (1,5 or 1.5).
std::optional<double> parse_cell_number(std::string_view cell, char separator) {
    const std::size_t comma = cell.find(',');
    if (separator != ';' || comma == std::string_view::npos) return parse_number(cell);
    std::string pointed(cell);
    pointed[comma] = '.';
    return parse_number(pointed);
}

columns parse_header(const std::vector<std::string_view>& cells, char separator, const std::string& where,
                     warnings& warn) {
    if (cells.size() == 1 && trim(cells[0]).find_first_of(" \t") != std::string_view::npos)
        throw input_error(where, fmt::format("expected commas (or semicolons) between the columns, got '{}'",
                                             trim(cells[0]).substr(0, 40)));
    columns cols;
    cols.separator = separator;
    cols.count = cells.size();
    std::map<std::string, std::size_t> index;
    for (std::size_t i = 0; i < cells.size(); ++i) {
        const std::string name = ascii_lower(trim(cells[i]));
        if (name.empty()) continue;  // pandas' to_csv writes its index so; ignored as unknown columns are
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
    if (!cols.time) cols.time = claim("t");  // slerp's tables
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

    const auto vector_columns = [&](const auto& names, std::string_view what) {
        std::optional<std::array<std::size_t, 3>> at;
        const auto x = claim(names[0]), y = claim(names[1]), z = claim(names[2]);
        if (!x && !y && !z) return at;
        if (!(x && y && z)) throw input_error(where, fmt::format("{} needs all of the columns {}", what, fmt::join(names, " ")));
        return at = std::array<std::size_t, 3>{*x, *y, *z};
    };
    cols.translation = vector_columns(translation_columns, "translation");
    if (cols.translation && cols.kind == rep::matrix4)
        throw input_error(where, "4x4 matrix and tx ty tz columns: expected one translation per key");
    cols.scale = vector_columns(scale_columns, "scale");
    cols.velocity = vector_columns(velocity_columns, "angular velocity");
    cols.acceleration = vector_columns(acceleration_columns, "angular acceleration");
    for (std::size_t n = 0; n < index.size(); ++n) {  // w0 ... wN-1, one after another
        const auto at = claim(weight_column(n));
        if (!at) break;
        cols.weights.push_back(*at);
    }
    for (const auto& [name, at] : index)
        if (!known[at] && name.size() > 1 && name[0] == 'w' &&
            name.find_first_not_of("0123456789", 1) == std::string::npos)
            throw input_error(where, fmt::format("column '{}' without '{}': expected the morph weights' columns w0 to "
                                                 "wN-1, each once",
                                                 name, weight_column(cols.weights.size())));
    cols.plain = separator == ',' && cols.count <= max_plain_cells &&
                 std::all_of(known.begin(), known.end(), [](bool k) { return k; });
    for (std::size_t i = 0; i < cells.size(); ++i)
        if (!known[i])
            warn.once("column", trim(cells[i]).empty() ? fmt::format("ignoring unnamed column {}", i + 1)
                                                       : fmt::format("ignoring unknown column '{}'", trim(cells[i])));
    return cols;
}

bool empty_cell(const std::vector<std::string_view>& cells, std::size_t at) { return trim(cells[at]).empty(); }

/// Blank lines and comments; and anything that is not UTF-8 is an error.
bool skipped(std::string_view line, const std::string& source, std::size_t number) {
    const std::string_view content = trim(line);
    if (content.empty() || content.front() == '#') return true;
    if (!is_valid_utf8(line))
        throw input_error(where(source, number),
                          number == 1 && looks_like_utf16(line) ? utf16_message : "invalid UTF-8: expected text");
    return false;
}

/// The keys on the rows of a table whose header is read: each row apart
/// from the others, so that copies on several threads can share the rows
/// (read_ahead).
class csv_rows final : public line_parser {
public:
    csv_rows(columns cols, std::string source)
        : cols_(std::move(cols)), source_(std::move(source)), splitter_(cols_.separator) {}
    const columns& cols() const noexcept { return cols_; }

    bool parse(std::string_view line, const text_place& place, std::string& track, raw_key& k) override {
        const std::size_t line_no = place.line;
        if (read_plain(line, line_no, track, k)) return true;
        if (skipped(line, source_, line_no)) return false;
        const auto where = [&] { return keyrot::where(source_, line_no); };
        const auto& cells = splitter_.split(line, source_, line_no);
        if (cells.size() != cols_.count)
            throw input_error(where(), fmt::format("expected {} cells as in the header, got {}", cols_.count, cells.size()));
        const auto number = [&](std::size_t at, std::string_view name) {
            if (auto v = parse_cell_number(cells[at], cols_.separator)) return *v;
            throw input_error(where(), fmt::format("column '{}': expected a finite number, got '{}'", name,
                                                   trim(cells[at]).substr(0, 40)));
        };
        new_key(k, line_no);
        if (cols_.time && !(cols_.frame && empty_cell(cells, *cols_.time))) k.time = number(*cols_.time, "time");
        if (cols_.frame && !(cols_.time && empty_cell(cells, *cols_.frame))) k.frame = number(*cols_.frame, "frame");
        if (!k.time && !k.frame) throw input_error(where(), "no time: expected a 'time' or a 'frame'");
        const auto names = rotation_columns(cols_.kind, quat_order::wxyz);
        for (std::size_t i = 0; i < cols_.rotation.size(); ++i) k.values[i] = number(cols_.rotation[i], names[i]);
        const auto vector = [&](const std::optional<std::array<std::size_t, 3>>& at, const auto& column) {
            std::optional<vec3> v;
            if (!at) return v;
            const auto& c = *at;
            const int empty = empty_cell(cells, c[0]) + empty_cell(cells, c[1]) + empty_cell(cells, c[2]);
            if (empty == 0) v = vec3{number(c[0], column[0]), number(c[1], column[1]), number(c[2], column[2])};
            else if (empty != 3)
                throw input_error(where(), fmt::format("columns {}: expected three numbers or three empty cells",
                                                       fmt::join(column, " ")));
            return v;
        };
        k.translation = vector(cols_.translation, translation_columns);
        k.scale = vector(cols_.scale, scale_columns);
        k.rates = {vector(cols_.velocity, velocity_columns), vector(cols_.acceleration, acceleration_columns)};
        // A track with fewer morph targets than the table's columns leaves the last of them empty.
        for (std::size_t i = 0; i < cols_.weights.size(); ++i) {
            if (empty_cell(cells, cols_.weights[i])) continue;
            if (k.weights.size() != i)
                throw input_error(where(), fmt::format("column '{}' after an empty '{}': expected the weights as "
                                                       "numbers from w0 on, and the columns after them empty",
                                                       weight_column(i), weight_column(k.weights.size())));
            k.weights.push_back(number(cols_.weights[i], weight_column(i)));
        }
        track.clear();
        if (cols_.track) {
            track = splitter_.text(*cols_.track);
            if (track.empty()) throw input_error(where(), "column 'track': expected a track name, got an empty cell");
            check_track_name(track, where());
        }
        return true;
    }

private:
    /// The common row, read without splitting it into cells first: numbers
    /// and a track name, no ignored columns. Each number may have spaces or
    /// tabs around it, but no '+', quotes or empty cells; a track name is
    /// printable ASCII without quotes or '#'. Such rows are all parse()
    /// would accept, and read the same. False for any other line, which
    /// parse() then reads cell by cell (and words the error for, if need be).
    bool read_plain(std::string_view line, std::size_t line_no, std::string& track, raw_key& k) const {
        if (!cols_.plain) return false;
        std::array<double, max_plain_cells> cell;
        std::string_view name;
        const char* p = line.data();
        const char* const end = p + line.size();
        for (std::size_t i = 0; i < cols_.count; ++i) {
            if (i > 0 && (p == end || *p++ != ',')) return false;
            if (i == cols_.track) {
                const char* const start = p;
                for (; p != end && *p != ','; ++p)
                    if (*p < ' ' || *p > '~' || *p == '"' || *p == '#') return false;
                name = trim(std::string_view(start, static_cast<std::size_t>(p - start)));
                if (name.empty()) return false;
                continue;
            }
            p = after_blanks(p, end);
            const auto [stop, ec] = std::from_chars(p, end, cell[i]);
            if (ec != std::errc{} || !std::isfinite(cell[i])) return false;
            p = after_blanks(stop, end);
        }
        if (p != end) return false;
        new_key(k, line_no);
        if (cols_.time) k.time = cell[*cols_.time];
        if (cols_.frame) k.frame = cell[*cols_.frame];
        for (std::size_t i = 0; i < cols_.rotation.size(); ++i) k.values[i] = cell[cols_.rotation[i]];
        if (const auto& t = cols_.translation) k.translation = vec3{cell[(*t)[0]], cell[(*t)[1]], cell[(*t)[2]]};
        if (const auto& s = cols_.scale) k.scale = vec3{cell[(*s)[0]], cell[(*s)[1]], cell[(*s)[2]]};
        for (const std::size_t w : cols_.weights) k.weights.push_back(cell[w]);
        if (const auto& v = cols_.velocity) k.rates.velocity = vec3{cell[(*v)[0]], cell[(*v)[1]], cell[(*v)[2]]};
        if (const auto& a = cols_.acceleration) k.rates.acceleration = vec3{cell[(*a)[0]], cell[(*a)[1]], cell[(*a)[2]]};
        if (track != name) track = name;  // (most rows are of the track before: a compare costs less than a copy)
        return true;
    }

    static const char* after_blanks(const char* p, const char* end) noexcept {
        while (p != end && (*p == ' ' || *p == '\t')) ++p;
        return p;
    }

    void new_key(raw_key& k, std::size_t line_no) const {
        k.reset();
        k.at.line = line_no;
        k.kind = cols_.kind;
    }

    columns cols_;
    std::string source_;
    cell_splitter splitter_;
};

class csv_reader final : public line_key_reader {
public:
    csv_reader(std::istream& in, const read_options& opts, warnings& warn)
        : lines_(in, opts.max_line_bytes, opts.source), settings_(opts.settings) {
        // numpy.savetxt writes its header as a comment ("# time,qw,..."):
        // the last comment before the first row is the header when it names
        // a time column and the row does not.
        const std::string& source = opts.source;
        cell_splitter splitter;
        std::string comment;
        std::size_t comment_line = 0;  // 0: the last comment (if any) names no time column
        std::string_view line;
        while (lines_.next(line)) {
            if (skipped(line, source, lines_.number())) {
                const auto content = trim(line);
                if (content.empty()) continue;  // a blank line
                if (content.starts_with(csv_settings_comment)) {
                    read_settings(content.substr(csv_settings_comment.size()), opts, lines_.number(), warn);
                    comment_line = 0;
                    continue;
                }
                comment_line = names_time(content.substr(1)) ? lines_.number() : 0;
                if (comment_line != 0) comment = content.substr(1);
                continue;
            }
            if (comment_line != 0 && !names_time(line)) {
                lines_.put_back();  // the first key, read with the header
                header_line_ = comment_line;
                rows_.emplace(parse_header(splitter.split(comment, source, comment_line), ',',
                                           where(source, comment_line), warn),
                              source);
                return;
            }
            const std::string where = keyrot::where(source, lines_.number());
            if (looks_like_utf16(line)) throw input_error(where, utf16_message);  // (no byte-order mark)
            if (const char c = trim(line).front(); c == '{' || c == '[')
                throw input_error(where, fmt::format("expected a CSV header, got what looks like JSON ('{}'): "
                                                     "--from json or --from ndjson reads it as such",
                                                     c));
            const char separator = separator_of(line);
            cell_splitter by_separator(separator);
            const auto& cells = by_separator.split(line, source, lines_.number());
            if (std::all_of(cells.begin(), cells.end(), [](auto c) { return parse_number(c).has_value(); }))
                throw input_error(where, "expected a header line naming the columns (time or frame, and "
                                         "the rotation's), got a row of numbers");
            header_line_ = lines_.number();
            rows_.emplace(parse_header(cells, separator, where, warn), source);
            return;
        }
        throw input_error(source, "empty input: expected a CSV header and keys");
    }

    bool named() const override { return rows_->cols().track.has_value(); }
    location start() const override { return {header_line_, {}}; }
    const key_settings& settings() const override { return settings_; }

    bool next(std::string& track, raw_key& k) override { return next_parsed(*rows_, track, k); }

    bool next_line(std::string_view& line, text_place& at) override {
        if (!lines_.next(line)) return false;
        at.line = lines_.number();
        return true;
    }

    std::unique_ptr<line_parser> parser() const override { return std::make_unique<csv_rows>(*rows_); }

private:
    /// The settings of a "# keyrot {...}" line, over the flags'.
    void read_settings(std::string_view object, const read_options& opts, std::size_t line_no, warnings& warn) {
        const std::string where = keyrot::where(opts.source, line_no);
        flat_json settings;
        if (!settings.parse(object) || !settings.root().is_object())
            throw input_error(where, fmt::format("expected a JSON object of settings after '{}'", trim(csv_settings_comment)));
        // CSV names its quaternion columns: an order stated or typed changes nothing.
        read_options ignoring_order = opts;
        ignoring_order.given.order = false;
        quat_order order = opts.order;
        detail::apply_fields(settings.root(), settings_, order, where, detail::settings_object::header, ignoring_order,
                             warn);
    }

    /// Whether a line has a cell 'time' or 'frame' (any case, unquoted).
    static bool names_time(std::string_view line) {
        for (std::size_t start = 0; start <= line.size();) {
            const std::size_t comma = std::min(line.find(',', start), line.size());
            const std::string_view cell = trim(line.substr(start, comma - start));
            if (cell.size() <= 5 && (ascii_lower(cell) == "time" || ascii_lower(cell) == "frame")) return true;
            start = comma + 1;
        }
        return false;
    }

    line_reader lines_;
    key_settings settings_;
    std::optional<csv_rows> rows_;  // once the header is read
    std::size_t header_line_ = 0;
};

}  // namespace

std::unique_ptr<line_key_reader> make_csv_reader(std::istream& in, const read_options& opts, warnings& warn) {
    return std::make_unique<csv_reader>(in, opts, warn);
}

}  // namespace keyrot
