// SPDX-License-Identifier: MIT
#pragma once
// How keyrot speaks on stderr: an error as one line "keyrot: <what>", and
// warnings about an input, each kind once.
#include <mutex>
#include <ostream>
#include <set>
#include <string>
#include <string_view>

namespace keyrot {

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
