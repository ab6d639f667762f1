// SPDX-License-Identifier: MIT
#pragma once
// JSON parsed in place into one flat array, reused from parse to parse:
// building nlohmann-json's map-based document took three quarters of the
// time NDJSON input spent. Only what this parser reads exactly as
// nlohmann-json would is taken: strings of UTF-8 (escapes decoded as it
// decodes them), unique member names (at most 256 to an object), strict
// JSON numbers, values at most 8 deep. Anything else (including every
// syntax error) is declined, and the caller asks nlohmann-json, which then
// also words the error.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace keyrot {

/// Appends the text of a JSON string, the bytes between its quotes, with
/// its escapes decoded as nlohmann-json decodes them (\u surrogate pairs
/// as one UTF-8 character). False, with `out` partly appended, for what it
/// refuses: an unknown or cut-short escape, a lone surrogate, a control
/// character, bytes that are not UTF-8.
bool append_json_string(std::string_view quoted, std::string& out);

class flat_json {
public:
    enum class kind : std::uint8_t { null, boolean, number, string, array, object };

private:
    struct span {  // trivial, for the union below
        std::uint32_t at, size;  // bytes of the text, or of decoded_ where size has decoded_bit
    };
    static constexpr std::uint32_t decoded_bit = std::uint32_t{1} << 31;
    struct item {
        kind type = kind::null;
        std::uint32_t next = 0;  // the parent's next element or member; 0: the last
        span name{};             // a member's name
        union {                  // by type: 24 bytes an item, where a document has millions
            double number = 0;
            span text;           // a string's bytes
            std::uint32_t size;  // an array's elements or an object's members, which follow the item
        };
        bool container() const noexcept { return type == kind::array || type == kind::object; }
    };

public:
    /// A value of the last text parsed, with the queries the JSON readers
    /// make (the same as their nlohmann-json counterparts).
    class value {
    public:
        kind type() const noexcept { return item().type; }
        /// As nlohmann-json's type_name(): "number", "array", ...
        std::string_view type_name() const noexcept;
        bool is_null() const noexcept { return type() == kind::null; }
        bool is_number() const noexcept { return type() == kind::number; }
        bool is_string() const noexcept { return type() == kind::string; }
        bool is_array() const noexcept { return type() == kind::array; }
        bool is_object() const noexcept { return type() == kind::object; }
        double number() const noexcept { return is_number() ? item().number : 0; }
        /// The string's bytes (is_string()), escapes decoded.
        std::string_view string() const noexcept { return is_string() ? json_->bytes(item().text) : std::string_view(); }
        /// Elements of an array, members of an object.
        std::size_t size() const noexcept { return item().container() ? item().size : 0; }
        /// Element i < size() of an array (i steps: for the first few).
        value operator[](std::size_t i) const noexcept;
        /// The member of an object by name.
        std::optional<value> member(std::string_view name) const noexcept;
        /// f(element) for each element of an array, in order.
        template <class F>
        void elements(F&& f) const {
            for (std::uint32_t at = first(); at != 0; at = json_->items_[at].next) f(value{*json_, at});
        }
        /// f(name, value) for each member of an object, in order.
        template <class F>
        void members(F&& f) const {
            for (std::uint32_t at = first(); at != 0; at = json_->items_[at].next)
                f(json_->bytes(json_->items_[at].name), value{*json_, at});
        }

    private:
        friend class flat_json;
        value(const flat_json& json, std::uint32_t index) : json_(&json), index_(index) {}
        const flat_json::item& item() const noexcept { return json_->items_[index_]; }
        std::uint32_t first() const noexcept { return size() == 0 ? 0 : index_ + 1; }

        const flat_json* json_;
        std::uint32_t index_;
    };

    /// At most `max_values` values in a text: a bound on a line's work.
    explicit flat_json(std::size_t max_values = SIZE_MAX) : max_values_(max_values) {}

    /// Parses `text` (which must outlive the values); false: declined.
    /// Example: `flat_json j; if (j.parse(R"({"time": 0})")) j.root().member("time")->number();`
    bool parse(std::string_view text);
    /// The top-level value of the last text parse() took.
    value root() const noexcept { return {*this, 0}; }

private:
    bool parse_value(int depth);
    bool parse_container(int depth, bool object);
    bool parse_string(span& out);
    bool parse_escaped_string(const char* begin, span& out);
    bool parse_number(double& out);
    bool parse_literal(std::string_view word);
    void skip_space() noexcept;
    std::string_view bytes(span s) const noexcept {
        if (s.size & decoded_bit) return {decoded_.data() + s.at, s.size & ~decoded_bit};
        return {begin_ + s.at, s.size};
    }

    std::size_t max_values_;
    std::vector<item> items_;
    std::string decoded_;  // strings with escapes, decoded
    const char* begin_ = nullptr;
    const char* p_ = nullptr;
    const char* end_ = nullptr;
};

}  // namespace keyrot
