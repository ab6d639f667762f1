#include "io/format.hpp"

#include <nlohmann/json.hpp>

#include "ground/text.hpp"

namespace keyrot {

std::optional<format> format_of_path(std::string_view path) {
    const auto dot = path.rfind('.');
    if (dot == std::string_view::npos || path.find('/', dot) != std::string_view::npos) return std::nullopt;
    const std::string ext = ascii_lower(path.substr(dot + 1));
    if (ext == "jsonl") return format::ndjson;
    return parse<format>(ext);
}

format sniff_format(std::string_view text) {
    text = without_bom(text);
    const auto start = text.find_first_not_of(" \t\r\n");
    if (start == std::string_view::npos) return format::csv;
    if (text[start] == '[') return format::json;
    if (text[start] != '{') return format::csv;
    // One object per line with more after it is NDJSON; so is a single line
    // holding one key or frame object.
    const auto eol = text.find('\n', start);
    const std::string_view first = text.substr(start, eol == std::string_view::npos ? eol : eol - start);
    const auto j = nlohmann::json::parse(first.begin(), first.end(), nullptr, false);
    if (j.is_discarded() || !j.is_object()) return format::json;
    const bool more = eol != std::string_view::npos && text.find_first_not_of(" \t\r\n", eol) != std::string_view::npos;
    return more || j.contains("time") || j.contains("frame") ? format::ndjson : format::json;
}

}  // namespace keyrot
