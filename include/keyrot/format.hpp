#pragma once
// The file formats by name, by extension, and by content.
#include <array>
#include <optional>
#include <string_view>

namespace keyrot {

enum class format { csv, json, ndjson };
inline constexpr std::array<std::string_view, 3> format_names = {"csv", "json", "ndjson"};
/// "csv" -> format::csv; std::nullopt for a name not in format_names.
std::optional<format> parse_format(std::string_view name);
std::string_view to_string(format f) noexcept;
/// ".csv" -> csv, ".json" -> json, ".ndjson" / ".jsonl" -> ndjson.
std::optional<format> format_of_path(std::string_view path);
/// Guess from the start of the content: '{' or '[' first means JSON, unless
/// the first line is a whole object and more lines follow (NDJSON); else CSV.
format sniff_format(std::string_view start);

}  // namespace keyrot
