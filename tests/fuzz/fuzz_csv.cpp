// SPDX-License-Identifier: MIT
// libFuzzer target: the CSV reader and key validation on arbitrary bytes.
// Any exception but keyrot::error, any sanitizer report, or a key that is
// not a finite unit quaternion is a finding; so is a table whose rows read
// otherwise in one pass (the fast path for plain rows) than cell by cell.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

#include "check.hpp"
#include "ground/text.hpp"
#include "io/document.hpp"

namespace {

/// `text` with every cell of the rows after the header quoted, blank lines
/// as they are: the same table, but rows the reader must split into cells.
/// The spaces around a cell stay outside its quotes (a quoted cell keeps
/// the spaces inside). std::nullopt where quoting would change what the
/// text says: quotes, comments and carriage returns (a line's end).
std::optional<std::string> with_quoted_cells(std::string_view text) {
    if (text.find_first_of("\"#\r") != std::string_view::npos) return std::nullopt;
    std::string out;
    bool header = true;
    for (bool first = true; !text.empty(); first = false) {
        const std::size_t nl = text.find('\n');
        const std::string_view line = text.substr(0, nl);
        text.remove_prefix(nl == std::string_view::npos ? text.size() : nl + 1);
        const bool blank = keyrot::trim(first ? keyrot::without_bom(line) : line).empty();  // a BOM alone is blank
        if (header || blank) {
            header = header && blank;  // blank lines before the header stay blank
            out += line;
        } else {
            for (std::size_t start = 0; start <= line.size();) {
                const std::size_t comma = std::min(line.find(',', start), line.size());
                const std::string_view cell = line.substr(start, comma - start), content = keyrot::trim(cell);
                const std::size_t lead = content.empty() ? cell.size() : static_cast<std::size_t>(content.data() - cell.data());
                out.append(cell.substr(0, lead)).append("\"").append(content).append("\"");
                out.append(cell.substr(std::min(cell.size(), lead + content.size())));
                if (comma < line.size()) out += ',';
                start = comma + 1;
            }
        }
        if (nl != std::string_view::npos) out += '\n';
    }
    return out;
}

/// `text` read as compare and info read it; none where that fails.
std::optional<keyrot::document> read_csv(std::string_view text, keyrot::warnings& warn) {
    keyrot::read_options opts;
    opts.source = "fuzz.csv";
    opts.settings.euler = keyrot::parse_euler_seq("ZYX");
    std::istringstream in{std::string(text)};
    try {
        return keyrot::read_document(in, keyrot::format::csv, opts, warn);
    } catch (const keyrot::error&) {
        return std::nullopt;
    }
}

bool same_bits(std::optional<double> a, std::optional<double> b) {
    return a.has_value() == b.has_value() && (!a || std::memcmp(&*a, &*b, sizeof(double)) == 0);
}

bool same_vector(const std::optional<keyrot::vec3>& a, const std::optional<keyrot::vec3>& b) {
    return a.has_value() == b.has_value() && (!a || std::memcmp(&*a, &*b, sizeof(keyrot::vec3)) == 0);
}

/// Both unread, or the same tracks of the same keys, to the bit.
bool same_keys(const std::optional<keyrot::document>& a, const std::optional<keyrot::document>& b) {
    if (!a || !b) return !a && !b;
    if (a->named != b->named || a->tracks.size() != b->tracks.size()) return false;
    for (std::size_t t = 0; t < a->tracks.size(); ++t) {
        const auto &x = a->tracks[t].keys, &y = b->tracks[t].keys;
        if (a->tracks[t].name != b->tracks[t].name || x.size() != y.size()) return false;
        for (std::size_t i = 0; i < x.size(); ++i) {
            const bool same = x[i].at.line == y[i].at.line && x[i].given_as == y[i].given_as &&
                              same_bits(x[i].time, y[i].time) && same_bits(x[i].frame, y[i].frame) &&
                              std::memcmp(&x[i].rotation, &y[i].rotation, sizeof(keyrot::quat)) == 0 &&
                              same_vector(x[i].translation, y[i].translation) && same_vector(x[i].scale, y[i].scale);
            if (!same) return false;
        }
    }
    return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::ostringstream err;
    keyrot::warnings warn(err, "fuzz.csv");
    const auto text = keyrot::fuzz::text(data, size);
    const auto doc = read_csv(text, warn);
    if (doc)
        for (const auto& t : doc->tracks) keyrot::fuzz::check_track(t);
    if (const auto quoted = with_quoted_cells(text)) keyrot::fuzz::require(same_keys(doc, read_csv(*quoted, warn)));
    return 0;
}
