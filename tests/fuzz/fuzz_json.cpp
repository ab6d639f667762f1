// libFuzzer target: the JSON and NDJSON readers and key validation.
#include <cstddef>
#include <cstdint>
#include <sstream>

#include "check.hpp"
#include "keyrot/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::ostringstream err;
    keyrot::warnings warn(err, "fuzz.json");
    keyrot::read_options opts;
    opts.source = "fuzz.json";
    const auto text = keyrot::fuzz::text(data, size);
    for (const keyrot::format f : {keyrot::format::json, keyrot::format::ndjson}) {
        try {
            const auto doc = keyrot::read_document(text, f, opts, warn);
            for (const auto& raw : doc.tracks) keyrot::fuzz::check_track(keyrot::make_track(raw, warn));
        } catch (const keyrot::error&) {
        }
    }
    return 0;
}
