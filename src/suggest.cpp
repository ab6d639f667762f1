// SPDX-License-Identifier: MIT
#include "suggest.hpp"

#include <algorithm>

#include "ground/text.hpp"

namespace keyrot {

std::size_t edit_distance(std::string_view a_text, std::string_view b_text) {
    const std::string a = ascii_lower(a_text), b = ascii_lower(b_text);
    std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
    for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
        for (std::size_t j = 1; j <= b.size(); ++j) {
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

std::string nearest(std::string_view word, const std::vector<std::string>& names) {
    return *std::min_element(names.begin(), names.end(), [&](const auto& x, const auto& y) {
        return edit_distance(word, x) < edit_distance(word, y);
    });
}

std::optional<std::string> likely_meant(std::string_view word, const std::vector<std::string>& names,
                                        std::size_t letters) {
    if (names.empty()) return std::nullopt;
    const std::string nearest_name = nearest(word, names);
    const std::size_t edits = edit_distance(word, nearest_name);
    const auto as_near = std::ranges::count_if(names, [&](const std::string& name) { return edit_distance(word, name) == edits; });
    if (edits <= (letters <= 4 ? 1u : 2u) && as_near == 1) return nearest_name;  // "xyz": wxyz or xyzw?
    const std::string lower = ascii_lower(word);
    std::string longest;  // spelt out in full
    for (const std::string& name : names)
        if (name.size() >= 3 && name.size() > longest.size() && lower.starts_with(ascii_lower(name))) longest = name;
    if (longest.empty()) return std::nullopt;
    return longest;
}

}  // namespace keyrot
