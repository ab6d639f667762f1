// SPDX-License-Identifier: MIT
#include "io/csv/csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <deque>
#include <optional>
#include <utility>

#include "ground/text.hpp"
#include "io/common/columns.hpp"
#include "io/common/line_reader.hpp"
#include "io/json/flat_json.hpp"
#include "io/json/json_keys.hpp"

namespace keyrot {
namespace {

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
struct columns : column_layout {
    /// ',' or ';': a semicolon-separated table, whose numbers may have a
    /// decimal comma (what a spreadsheet saves as CSV in many locales).
    char separator = ',';
    bool plain = false;  // no ignored columns, at most max_plain_cells: rows for csv_rows::read_plain
};

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
    static_cast<column_layout&>(cols) = layout_of(cells, where);
    cols.separator = separator;
    cols.plain = separator == ',' && cols.count <= max_plain_cells &&
                 std::all_of(cols.known.begin(), cols.known.end(), [](bool k) { return k; });
    for (std::size_t i = 0; i < cells.size(); ++i)
        if (!cols.known[i])
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

/// A row's cells as read_row reads them.
struct csv_cells {
    const std::vector<std::string_view>& cells;
    const cell_splitter& splitter;
    char separator;
    const std::string& source;
    std::size_t line;

    bool empty(std::size_t at) const { return empty_cell(cells, at); }
    double number(std::size_t at, std::string_view name) const {
        if (auto v = parse_cell_number(cells[at], separator)) return *v;
        fail(fmt::format("column '{}': expected a finite number, got '{}'", name, trim(cells[at]).substr(0, 40)));
    }
    std::string text(std::size_t at) const {
        std::string name(splitter.text(at));
        if (!name.empty()) check_track_name(name, where(source, line));
        return name;
    }
    [[noreturn]] void fail(const std::string& message) const { throw input_error(where(source, line), message); }
};

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
        const auto& cells = splitter_.split(line, source_, line_no);
        const csv_cells row{cells, splitter_, cols_.separator, source_, line_no};
        if (cells.size() != cols_.count)
            row.fail(fmt::format("expected {} cells as in the header, got {}", cols_.count, cells.size()));
        new_key(k, line_no);
        read_row(cols_, row, track, k);
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
        k.angles = cols_.angles;
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
        ignoring_order.order_given = false;
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
