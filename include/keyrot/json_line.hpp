#pragma once
// One NDJSON line parsed in place, without allocating once warm: nlohmann-json
// builds a map-based document per line, which took three quarters of the
// time NDJSON input spends. Only what this parser takes exactly as
// nlohmann-json would is taken: strings of printable ASCII without escapes,
// small values, unique names, strict JSON numbers. Anything else (including
// every syntax error) is declined, and the caller asks nlohmann-json, which
// then also words the error.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace keyrot {

class json_line {
public:
    enum class kind : std::uint8_t { null, boolean, number, string, array, object };

private:
    struct item {
        kind type = kind::null;
        std::uint32_t size = 0;   // elements or members
        std::uint32_t first = 0;  // first element or member; 0: none (the root is never one)
        std::uint32_t next = 0;   // the next element or member of the parent; 0: last
        double number = 0;
        std::string_view text;  // a string's bytes
        std::string_view name;  // a member's name
    };

public:
    /// A value of the last line parsed, with the queries the key readers
    /// make (the same as their nlohmann-json counterparts).
    class value {
    public:
        kind type() const noexcept { return item().type; }
        /// As nlohmann-json's type_name(): "number", "array", ...
        std::string_view type_name() const noexcept;
        bool is_number() const noexcept { return type() == kind::number; }
        bool is_string() const noexcept { return type() == kind::string; }
        bool is_array() const noexcept { return type() == kind::array; }
        bool is_object() const noexcept { return type() == kind::object; }
        double number() const noexcept { return item().number; }
        /// The string's bytes (is_string()); they need no unescaping.
        std::string_view string() const noexcept { return item().text; }
        /// Elements of an array, members of an object.
        std::size_t size() const noexcept { return item().size; }
        /// Element i < size() of an array, or member i of an object.
        value operator[](std::size_t i) const noexcept;
        /// The member of an object by name.
        std::optional<value> member(std::string_view name) const noexcept;
        /// Its name as a member of an object; "" for an element or the root.
        std::string_view name() const noexcept { return item().name; }

    private:
        friend class json_line;
        value(const json_line& line, std::uint32_t index) : line_(&line), index_(index) {}
        const json_line::item& item() const noexcept { return line_->items_[index_]; }

        const json_line* line_;
        std::uint32_t index_;
    };

    /// Parses `text` (valid until the next parse); false: declined.
    /// Example: `json_line j; if (j.parse(R"({"time": 0})")) j.root().member("time")->number();`
    bool parse(std::string_view text);
    /// The top-level value of the last line parse() took.
    value root() const noexcept { return {*this, 0}; }

private:
    bool parse_value(int depth);
    bool parse_container(int depth, bool object);
    bool parse_string(std::string_view& out);
    bool parse_number(double& out);
    bool parse_literal(std::string_view word);
    void skip_space() noexcept;

    std::vector<item> items_;
    const char* p_ = nullptr;
    const char* end_ = nullptr;
};

}  // namespace keyrot
