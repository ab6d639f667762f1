// SPDX-License-Identifier: MIT
// libFuzzer target: glTF input (the first byte picks .glb or .gltf, and
// resample or convert), written as a .glb, which must read back: what keyrot
// writes, keyrot reads. Any exception but keyrot::error, a sanitizer
// report, or a message that is not one printable "keyrot: " line is a
// finding.
#include <cstddef>
#include <cstdint>
#include <iostream>
#include <sstream>

#include "app/app.hpp"
#include "check.hpp"
#include "standard_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace keyrot;
    if (size == 0) return 0;
    options o;
    o.cmd = data[0] & 1u ? command::convert : command::resample;
    o.from = data[0] & 2u ? format::glb : format::gltf;
    o.to = format::glb;
    o.max_frames = 1e5;  // keeps each run short
    fuzz::set_standard_input(reinterpret_cast<const char*>(data) + 1, size - 1);
    std::ostringstream out, err;
    int status = 2;
    try {
        status = run(o, std::cin, out, err);
    } catch (const usage_error&) {
    }
    fuzz::check_output(err.str());
    if (status != 0) return 0;
    // The output reads back.
    const std::string written = out.str();
    fuzz::set_standard_input(written.data(), written.size());
    options back;
    back.cmd = command::convert;
    back.from = format::glb;
    back.to = format::csv;
    std::ostringstream csv, back_err;
    fuzz::require(run(back, std::cin, csv, back_err) == 0);
    fuzz::check_output(back_err.str());
    return 0;
}
