#pragma once
// The file formats by name, by extension, and by content.
#include <array>
#include <optional>
#include <string_view>

#include "keyrot/names.hpp"

namespace keyrot {

enum class format { csv, json, ndjson };
template <>
inline constexpr std::array<enum_name<format>, 3> names_of<format> = {
    {{format::csv, "csv"}, {format::json, "json"}, {format::ndjson, "ndjson"}}};
/// Most bytes a CSV or NDJSON line, or a JSON document read whole, may take
/// (--max-bytes): endless input (/dev/zero) ends in an error, not in all memory.
inline constexpr std::size_t default_max_bytes = std::size_t{256} << 20;

/// ".csv" -> csv, ".json" -> json, ".ndjson" / ".jsonl" -> ndjson.
std::optional<format> format_of_path(std::string_view path);
/// Guess from the start of the content: '{' or '[' first means JSON, unless
/// the first line is a whole object and more lines follow (NDJSON); else CSV.
format sniff_format(std::string_view start);

}  // namespace keyrot
