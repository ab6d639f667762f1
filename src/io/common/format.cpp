// SPDX-License-Identifier: MIT
#include "io/common/format.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>

#include "ground/text.hpp"

namespace keyrot {

std::optional<format> format_of_path(std::string_view path) {
    const auto dot = path.rfind('.');
    if (dot == std::string_view::npos || path.find('/', dot) != std::string_view::npos) return std::nullopt;
    const std::string ext = ascii_lower(path.substr(dot + 1));
    if (ext == "jsonl") return format::ndjson;
    return parse<format>(ext);
}

namespace {

/// `"asset": {` somewhere in `text`: what a glTF file must have, and a
/// keyframe document has no use for.
bool has_asset_object(std::string_view text) {
    const auto after_blanks = [&](std::size_t i) { return std::min(text.find_first_not_of(" \t\r\n", i), text.size()); };
    for (auto at = text.find("\"asset\""); at != std::string_view::npos; at = text.find("\"asset\"", at + 1)) {
        const std::size_t colon = after_blanks(at + 7);
        if (colon < text.size() && text[colon] == ':') {
            const std::size_t brace = after_blanks(colon + 1);
            if (brace < text.size() && text[brace] == '{') return true;
        }
    }
    return false;
}

}  // namespace

format sniff_format(std::string_view text) {
    if (text.starts_with("glTF")) return format::glb;
    text = without_bom(text);
    const auto start = text.find_first_not_of(" \t\r\n");
    if (start == std::string_view::npos) return format::csv;
    if (ascii_lower(text.substr(start, 9)) == "hierarchy") return format::bvh;
    if (text[start] == '[') return format::json;
    if (text[start] != '{') return format::csv;
    if (has_asset_object(text) && text.find("\"version\"") != std::string_view::npos) return format::gltf;
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
