// SPDX-License-Identifier: MIT
// libFuzzer target: BVH on arbitrary bytes. The reader's keys must be
// finite unit quaternions at increasing times; through the command (the
// first byte picks convert or resample, to BVH or CSV), a message that is
// not one printable "keyrot: " line is a finding, what keyrot writes must
// read back, and convert to BVH must give back the input's own channel
// values, number for number.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "command.hpp"
#include "io/document.hpp"

namespace {

/// The numbers after the "Frame Time:" line, in order.
std::vector<double> motion_values(std::string_view bvh) {
    const std::size_t header = bvh.rfind("Frame Time:");  // (the last: a joint may be named so, no value can)
    keyrot::fuzz::require(header != std::string_view::npos);
    const std::size_t start = bvh.find('\n', header);
    std::istringstream in{std::string(bvh.substr(start == std::string_view::npos ? bvh.size() : start))};
    std::vector<double> values;
    for (std::string word; in >> word;) values.push_back(std::strtod(word.c_str(), nullptr));
    return values;
}

/// `cmd` on `input`, read as `from` and written as `to`.
keyrot::fuzz::command_run run_command(keyrot::command cmd, keyrot::format from, keyrot::format to, std::string_view input) {
    keyrot::options o;
    o.cmd = cmd;
    o.from = from;
    o.to = to;
    o.max_frames = 1e5;  // keeps each run short
    return keyrot::fuzz::run_command(o, input);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace keyrot;
    if (size == 0) return 0;
    const std::string_view bvh = fuzz::text(data + 1, size - 1);

    read_options ro;
    ro.source = "fuzz.bvh";
    std::ostringstream warned;
    warnings warn(warned, "fuzz.bvh");
    std::istringstream in{std::string(bvh)};
    bool read = false;
    try {
        for (const auto& t : read_document(in, format::bvh, ro, warn).tracks) fuzz::check_track(t);
        read = true;
    } catch (const error&) {
    }

    const command cmd = data[0] & 1u ? command::resample : command::convert;
    const format to = data[0] & 2u ? format::csv : format::bvh;
    const auto r = run_command(cmd, format::bvh, to, bvh);
    if (r.status != 0) return 0;
    fuzz::require(read);  // the command reads no more than the reader does
    fuzz::require(run_command(command::convert, to, format::csv, r.out).status == 0);  // what keyrot writes it reads
    if (to == format::bvh && cmd == command::convert) fuzz::require(motion_values(r.out) == motion_values(bvh));
    return 0;
}
