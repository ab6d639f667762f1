// SPDX-License-Identifier: MIT
#pragma once
// The command line's flags: each command's CLI11 definitions, and the
// options struct the raw values become.
#include <array>
#include <optional>
#include <string>

#include "app/app.hpp"

namespace CLI {
class App;
}

namespace keyrot::cli {

/// The flag values as CLI11 fills them, before they become typed options.
struct raw_flags {
    std::string from, to, rep, euler, out_euler, quat_order, method,
                        path = "shortest", from_rep = "quat", report,
                        settings_line, velocity_frame = "body";
    bool out_degrees = false, out_radians = false, ignore_extra = false;
    std::optional<int> precision;
    std::optional<double> key_fps;
    std::optional<int> jobs;
    std::string tol;  // an angle: degrees, or with a unit (0.1deg, 0.002rad)
};

/// A command: its name and description, and the flags it defines.
struct command_definition {
    const char* name;
    const char* description;
    command cmd;
    void (*define)(CLI::App&, options&, raw_flags&);
};

extern const std::array<command_definition, 7> commands;

/// Turns the raw flag values into typed options, checking what CLI11 cannot.
/// Throws usage_error.
void finish(options& o, const raw_flags& f);

}  // namespace keyrot::cli
