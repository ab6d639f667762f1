// SPDX-License-Identifier: MIT
#pragma once
// keyrot's exceptions: bad input data, and options that cannot apply.
// The program catches them once, at the top, and prints each as one line.
#include <optional>
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

/// The options that an option_error is about.
enum class option {
    method,          ///< the interpolation method
    euler_sequence,  ///< the Euler sequence a method or representation needs
};

/// Options that cannot apply, whatever the data: method::euler without an
/// Euler sequence. `which` names the option, so that a front end can say
/// the message in its own terms (its flags); a front end's own option
/// errors (a bad command line) have none.
struct option_error : error {
    option_error(option which_option, const std::string& message) : error(message), which(which_option) {}
    explicit option_error(const std::string& message) : error(message) {}
    std::optional<option> which;
};

/// Bad input data. `where` names the source and the line or key:
/// "walk.csv:14" or "walk.json: tracks.hip.keys[3]".
struct input_error : error {
    input_error(const std::string& where, const std::string& message)
        : error(where + ": " + message) {}
};

}  // namespace keyrot
