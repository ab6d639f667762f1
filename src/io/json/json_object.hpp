// SPDX-License-Identifier: MIT
#pragma once
// The JSON that keyrot's reports write (info, compare, reduce --report
// json): members in a fixed order, "name": value separated by ", ", and
// numbers as the table writers write them. nlohmann's dump would print
// 1.0 as "1.0", where the tables print "1", and lay members out in its own
// way; the reports are built member by member here instead.
#include <fmt/format.h>

#include <optional>
#include <string>
#include <string_view>

namespace keyrot {

/// A number as the writers write it (shortest round trip, "1" for 1.0), or
/// null for none.
std::string json_number(std::optional<double> v);

/// An object's members, one call each, written in the order of the calls:
///
///     json_object().count("keys", 3).number("tol", 0.5).object()  ==  R"({"keys": 3, "tol": 0.5})"
class json_object {
public:
    json_object& number(std::string_view name, std::optional<double> v) { return raw(name, json_number(v)); }
    json_object& count(std::string_view name, std::size_t n) { return raw(name, fmt::format("{}", n)); }
    json_object& flag(std::string_view name, bool b) { return raw(name, b ? "true" : "false"); }
    /// A string, quoted (throws input_error for invalid UTF-8, as json_quote).
    json_object& text(std::string_view name, std::string_view s);
    /// A value that is JSON already: an array, an object, null.
    json_object& raw(std::string_view name, std::string_view json);
    /// The members alone ("a": 1, "b": 2), for an object written in pieces.
    const std::string& members() const noexcept { return out_; }
    /// {"a": 1, "b": 2}
    std::string object() const { return '{' + out_ + '}'; }

private:
    std::string out_;
};

}  // namespace keyrot
