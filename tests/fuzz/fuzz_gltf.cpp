// SPDX-License-Identifier: MIT
// libFuzzer target: glTF input (the first byte picks .glb or .gltf, and
// resample or convert), written as a .glb, which must read back: what keyrot
// writes, keyrot reads. Any exception but keyrot::error, a sanitizer
// report, or a message that is not one printable "keyrot: " line is a
// finding.
#include <cstddef>
#include <cstdint>

#include "app/app.hpp"
#include "command.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace keyrot;
    if (size == 0) return 0;
    options o;
    o.cmd = data[0] & 1u ? command::convert : command::resample;
    o.from = data[0] & 2u ? format::glb : format::gltf;
    o.to = format::glb;
    o.max_frames = 1e5;  // keeps each run short
    const auto r = fuzz::run_command(o, fuzz::text(data + 1, size - 1));
    if (r.status != 0) return 0;
    // The output reads back.
    options back;
    back.cmd = command::convert;
    back.from = format::glb;
    back.to = format::csv;
    fuzz::require(fuzz::run_command(back, r.out).status == 0);
    return 0;
}
