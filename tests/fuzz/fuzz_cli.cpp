// SPDX-License-Identifier: MIT
// libFuzzer target: a whole command run in-process on a byte buffer. The
// first byte picks the command and flags, the rest is standard input. Any
// exception but keyrot::error, a sanitizer report, or a message that is not
// one printable "keyrot: " line is a finding.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "app/app.hpp"
#include "command.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace keyrot;
    if (size == 0) return 0;
    const unsigned pick = data[0];
    options o;
    static constexpr std::array<command, 4> commands = {command::resample, command::convert, command::info,
                                                        command::reduce};
    o.cmd = commands[pick & 3u];
    o.how = static_cast<method>((pick >> 2) % 5);
    if (o.cmd == command::info && (pick & 0x04u)) {  // half of info's picks draw instead, to standard output
        o.cmd = command::plot;
        o.output = "-";
        o.speed = pick & 0x80u;
    }
    o.way = (pick & 0x20u) ? path::direct : path::shortest;
    o.representation = static_cast<rep>((pick >> 6) % 6 == 3 && !(pick & 1u) ? 0 : (pick >> 6) % 6);
    o.euler = parse_euler_seq((pick & 0x10u) ? "zxz" : "YXZ");
    o.radians = pick & 0x40u;
    o.fps = (pick & 0x80u) ? 30 : 24;
    o.precision = (pick & 0x08u) ? std::optional<int>(3) : std::nullopt;
    o.tol_deg = (pick & 0x08u) ? 0 : 0.5;  // reduce: exact keys only, or many dropped
    o.max_frames = 1e5;  // keeps each run short; the limit itself is tested elsewhere
    const auto r = fuzz::run_command(o, fuzz::text(data + 1, size - 1));
    // A picture is a whole SVG document, or nothing.
    if (o.cmd == command::plot)
        fuzz::require(r.status == 0 ? r.out.starts_with("<?xml") && r.out.ends_with("</svg>\n") : r.out.empty());
    return 0;
}
