// SPDX-License-Identifier: MIT
#include "io/json/flat_json.hpp"

#include <charconv>
#include <cmath>

#include "ground/text.hpp"

namespace keyrot {
namespace {

// Deeper than any keyframe document (a 4x4 matrix in a named track is 7
// deep), and members checked for duplicates pairwise, so few: a hostile
// text costs nlohmann-json's time, never quadratic time here.
constexpr int max_depth = 8;
constexpr std::uint32_t max_members = 256;

bool is_digit(char c) noexcept { return c >= '0' && c <= '9'; }

/// The four hex digits at `at` in `text`, or -1.
long hex4(std::string_view text, std::size_t at) noexcept {
    if (at > text.size() || text.size() - at < 4) return -1;
    long code = 0;
    for (const char c : text.substr(at, 4)) {
        const int digit = is_digit(c) ? c - '0' : (c >= 'a' && c <= 'f') ? c - 'a' + 10 : (c >= 'A' && c <= 'F') ? c - 'A' + 10 : -1;
        if (digit < 0) return -1;
        code = code * 16 + digit;
    }
    return code;
}

void append_utf8(long code, std::string& out) {
    const auto byte = [](long b) { return static_cast<char>(b); };
    if (code < 0x80) {
        out += byte(code);
    } else if (code < 0x800) {
        out += byte(0xc0 | (code >> 6));
        out += byte(0x80 | (code & 0x3f));
    } else if (code < 0x10000) {
        out += byte(0xe0 | (code >> 12));
        out += byte(0x80 | ((code >> 6) & 0x3f));
        out += byte(0x80 | (code & 0x3f));
    } else {
        out += byte(0xf0 | (code >> 18));
        out += byte(0x80 | ((code >> 12) & 0x3f));
        out += byte(0x80 | ((code >> 6) & 0x3f));
        out += byte(0x80 | (code & 0x3f));
    }
}

}  // namespace

bool append_json_string(std::string_view quoted, std::string& out) {
    const std::size_t start = out.size();
    unsigned char high = 0;  // any byte past ASCII, not from an escape
    for (std::size_t i = 0; i < quoted.size(); ++i) {
        const auto c = static_cast<unsigned char>(quoted[i]);
        if (c < 0x20 || c == '"') return false;
        if (c != '\\') {
            out += static_cast<char>(c);
            high |= c;
            continue;
        }
        if (++i == quoted.size()) return false;
        switch (quoted[i]) {
            case '"': out += '"'; break;
            case '\\': out += '\\'; break;
            case '/': out += '/'; break;
            case 'b': out += '\b'; break;
            case 'f': out += '\f'; break;
            case 'n': out += '\n'; break;
            case 'r': out += '\r'; break;
            case 't': out += '\t'; break;
            case 'u': {
                long code = hex4(quoted, i + 1);
                i += 4;
                if (code >= 0xd800 && code <= 0xdbff) {  // a high surrogate: its low one must follow
                    const long low = quoted.substr(i + 1, 2) == "\\u" ? hex4(quoted, i + 3) : -1;
                    if (low < 0xdc00 || low > 0xdfff) return false;
                    code = 0x10000 + ((code - 0xd800) << 10) + (low - 0xdc00);
                    i += 6;
                } else if (code < 0 || (code >= 0xdc00 && code <= 0xdfff)) {
                    return false;
                }
                append_utf8(code, out);
                break;
            }
            default: return false;
        }
    }
    return (high & 0x80) == 0 || is_valid_utf8(std::string_view(out).substr(start));
}

std::string_view flat_json::value::type_name() const noexcept {
    switch (type()) {
        case kind::null: return "null";
        case kind::boolean: return "boolean";
        case kind::number: return "number";
        case kind::string: return "string";
        case kind::array: return "array";
        case kind::object: return "object";
    }
    return "";
}

flat_json::value flat_json::value::operator[](std::size_t i) const noexcept {
    std::uint32_t at = first();
    for (; i > 0; --i) at = json_->items_[at].next;
    return {*json_, at};
}

std::optional<flat_json::value> flat_json::value::member(std::string_view name) const noexcept {
    if (!is_object()) return std::nullopt;
    for (std::uint32_t at = first(); at != 0; at = json_->items_[at].next)
        if (json_->bytes(json_->items_[at].name) == name) return value{*json_, at};
    return std::nullopt;
}

bool flat_json::parse(std::string_view text) {
    items_.clear();
    decoded_.clear();
    if (text.size() > UINT32_MAX) return false;
    // A key takes about 16 bytes a value: room for that, so that a document
    // is not copied as it grows (untouched room costs no memory).
    items_.reserve(text.size() / 12);
    begin_ = p_ = text.data();
    end_ = p_ + text.size();
    skip_space();
    if (!parse_value(0)) return false;
    skip_space();
    return p_ == end_;
}

void flat_json::skip_space() noexcept {
    while (p_ != end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\n' || *p_ == '\r')) ++p_;
}

bool flat_json::parse_value(int depth) {
    if (p_ == end_ || items_.size() >= max_values_ || items_.size() == UINT32_MAX) return false;
    const auto index = items_.size();
    items_.emplace_back();
    switch (*p_) {
        case '{': return parse_container(depth, true);
        case '[': return parse_container(depth, false);
        case '"': items_[index].type = kind::string, items_[index].text = {}; return parse_string(items_[index].text);
        case 't': items_[index].type = kind::boolean; return parse_literal("true");
        case 'f': items_[index].type = kind::boolean; return parse_literal("false");
        case 'n': return parse_literal("null");
        default: items_[index].type = kind::number; return parse_number(items_[index].number);
    }
}

bool flat_json::parse_container(int depth, bool object) {
    if (depth == max_depth) return false;
    const auto index = items_.size() - 1;
    items_[index].type = object ? kind::object : kind::array;
    items_[index].size = 0;
    const char close = object ? '}' : ']';
    ++p_;
    skip_space();
    if (p_ != end_ && *p_ == close) {
        ++p_;
        return true;
    }
    std::uint32_t last = 0;
    while (true) {
        span name{};
        if (object) {
            if (p_ == end_ || *p_ != '"' || !parse_string(name) || items_[index].size == max_members) return false;
            // Duplicate names: nlohmann-json keeps the last; leave it to it.
            for (std::uint32_t at = last == 0 ? 0 : static_cast<std::uint32_t>(index + 1); at != 0; at = items_[at].next)
                if (bytes(items_[at].name) == bytes(name)) return false;
            skip_space();
            if (p_ == end_ || *p_ != ':') return false;
            ++p_;
            skip_space();
        }
        const auto element = static_cast<std::uint32_t>(items_.size());
        if (!parse_value(depth + 1)) return false;
        items_[element].name = name;
        if (last != 0) items_[last].next = element;
        last = element;
        ++items_[index].size;
        skip_space();
        if (p_ == end_ || (*p_ != close && *p_ != ',')) return false;
        if (*p_++ == close) return true;
        skip_space();
    }
}

bool flat_json::parse_string(span& out) {
    const char* const begin = ++p_;
    unsigned char high = 0;  // any byte past ASCII
    for (; p_ != end_; ++p_) {
        const auto c = static_cast<unsigned char>(*p_);
        if (c == '"') {
            out = {static_cast<std::uint32_t>(begin - begin_), static_cast<std::uint32_t>(p_ - begin)};
            ++p_;
            // (not UTF-8: nlohmann-json words the error)
            return out.size < decoded_bit && ((high & 0x80) == 0 || is_valid_utf8(std::string_view(begin, out.size)));
        }
        if (c == '\\') return parse_escaped_string(begin, out);
        if (c < 0x20) return false;  // nlohmann-json words the error
        high |= c;
    }
    return false;
}

bool flat_json::parse_escaped_string(const char* begin, span& out) {
    for (; p_ != end_ && *p_ != '"'; ++p_)  // to the closing quote: a backslash takes the byte after it
        if (*p_ == '\\' && ++p_ == end_) return false;
    if (p_ == end_) return false;
    const std::size_t at = decoded_.size();
    if (!append_json_string(std::string_view(begin, static_cast<std::size_t>(p_ - begin)), decoded_)) return false;
    ++p_;
    const std::size_t size = decoded_.size() - at;
    if (at > UINT32_MAX || size >= decoded_bit) return false;
    out = {static_cast<std::uint32_t>(at), static_cast<std::uint32_t>(size) | decoded_bit};
    return true;
}

bool flat_json::parse_literal(std::string_view word) {
    if (static_cast<std::size_t>(end_ - p_) < word.size() || std::string_view(p_, word.size()) != word) return false;
    p_ += word.size();
    return true;
}

// JSON's grammar exactly: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?
bool flat_json::parse_number(double& out) {
    const char* const begin = p_;
    if (p_ != end_ && *p_ == '-') ++p_;
    if (p_ == end_ || !is_digit(*p_)) return false;
    if (*p_++ != '0')
        while (p_ != end_ && is_digit(*p_)) ++p_;
    bool integer = true;
    if (p_ != end_ && *p_ == '.') {
        integer = false;
        if (++p_ == end_ || !is_digit(*p_)) return false;
        while (p_ != end_ && is_digit(*p_)) ++p_;
    }
    if (p_ != end_ && (*p_ == 'e' || *p_ == 'E')) {
        integer = false;
        if (++p_ != end_ && (*p_ == '+' || *p_ == '-')) ++p_;
        if (p_ == end_ || !is_digit(*p_)) return false;
        while (p_ != end_ && is_digit(*p_)) ++p_;
    }
    // Correctly rounded, as strtod and the integer conversions nlohmann-json
    // uses are; out of range (overflow, and underflow where from_chars
    // reports it) is left to it.
    const auto [end, ec] = std::from_chars(begin, p_, out);
    if (ec != std::errc{} || end != p_ || !std::isfinite(out)) return false;
    // nlohmann-json holds "-0" as the integer 0, which is +0.0 as a double.
    if (integer && out == 0) out = 0;
    return true;
}

}  // namespace keyrot
