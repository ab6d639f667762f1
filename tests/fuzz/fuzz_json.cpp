// libFuzzer target: the JSON and NDJSON readers and key validation, and
// flat_json against nlohmann-json.
#include <cstddef>
#include <cstdint>
#include <sstream>

#include "../json_same.hpp"
#include "check.hpp"
#include "keyrot/flat_json.hpp"
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
    // What flat_json takes, nlohmann-json must read as the same value.
    keyrot::flat_json flat;
    if (flat.parse(text)) {
        try {
            keyrot::fuzz::require(keyrot::test::same_json(nlohmann::ordered_json::parse(text), flat.root()));
        } catch (const nlohmann::json::exception&) {
            std::abort();
        }
    }
    return 0;
}
