#pragma once
// keyrot's exceptions. All are caught once, at the top, and printed as one
// line "keyrot: <what>" with exit status 2.
#include <mutex>
#include <ostream>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>

namespace keyrot {

/// `text` with control characters and bytes that are not UTF-8 written as
/// \xNN, so that a message quoting bad input stays one readable line:
/// printable("a\tb") = "a\\x09b".
std::string printable(std::string_view text);

/// How a message quotes input: `text` whole up to `max` bytes, else its
/// first `max` bytes (whole UTF-8 characters) and "...", so that a 50 MB
/// bad value still gives a readable line: excerpt("abcdef", 3) = "abc...".
std::string excerpt(std::string_view text, std::size_t max = 40);

struct error : std::runtime_error {
    /// The message made printable at once: what() is a C string, which a
    /// NUL byte quoted from the input would cut short. One line stays
    /// readable whatever was quoted into it: at most 4096 bytes.
    explicit error(const std::string& message) : std::runtime_error(printable(excerpt(message, 4096))) {}
};

/// A bad command line.
struct usage_error : error {
    using error::error;
};

/// Bad input data. `where` names the source and the line or key:
/// "walk.csv:14" or "walk.json: tracks.hip.keys[3]".
struct input_error : error {
    input_error(const std::string& where, const std::string& message)
        : error(where + ": " + message) {}
};

/// Prints "keyrot: <message>" as one printable line: print_error(err, "walk.csv:3: ...").
void print_error(std::ostream& err, std::string_view message);

/// Warnings for one input source, each kind printed at most once
/// ("one warning per file") as "keyrot: warning: <source>: <message>".
/// Safe to use from the reading and the formatting thread at once.
class warnings {
public:
    warnings(std::ostream& err, std::string source) : err_(err), source_(std::move(source)) {}
    void once(const std::string& kind, const std::string& message);
    const std::string& source() const noexcept { return source_; }
    /// An attempt's warnings, held back until it succeeded: `printed` (its
    /// text) is printed here, and what `other` said counts as said here.
    void adopt(warnings& other, std::string_view printed);

private:
    std::ostream& err_;
    std::string source_;
    std::mutex mutex_;
    std::set<std::string> said_;
};

}  // namespace keyrot
