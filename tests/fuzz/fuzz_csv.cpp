// libFuzzer target: the CSV reader and key validation on arbitrary bytes.
// Any exception but keyrot::error, any sanitizer report, or a key that is
// not a finite unit quaternion is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>

#include "check.hpp"
#include "keyrot/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::ostringstream err;
    keyrot::warnings warn(err, "fuzz.csv");
    keyrot::read_options opts;
    opts.source = "fuzz.csv";
    opts.settings.euler = keyrot::parse_euler_seq("ZYX");
    try {
        const auto doc = keyrot::read_document(keyrot::fuzz::text(data, size), keyrot::format::csv, opts, warn);
        for (const auto& raw : doc.tracks) keyrot::fuzz::check_track(keyrot::make_track(raw, warn));
    } catch (const keyrot::error&) {
    }
    return 0;
}
