// SPDX-License-Identifier: MIT
// libFuzzer target: the JSON and NDJSON readers and key validation,
// flat_json against nlohmann-json, and the streaming JSON reader against
// the whole document's.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "../support/json_same.hpp"
#include "check.hpp"
#include "io/common/interface.hpp"
#include "io/document.hpp"
#include "io/json/flat_json.hpp"
#include "io/json/json.hpp"
#include "io/open.hpp"

namespace {

/// A key with its track's name and settings, every number exactly.
std::string describe(const std::string& track, const keyrot::key_settings& s, const keyrot::raw_key& k) {
    const auto number = [](const std::optional<double>& v) { return v ? fmt::format("{}", *v) : "-"; };
    std::string out = fmt::format("{} {} {} {} {} {} {} {} [{}]", track, static_cast<int>(s.angles),
                                  s.euler ? s.euler->name : "-", s.frame_rate(), k.at.path, number(k.time),
                                  number(k.frame), static_cast<int>(k.kind), fmt::join(k.values, " "));
    if (k.translation) out += fmt::format(" {} {} {}", k.translation->x, k.translation->y, k.translation->z);
    if (k.scale) out += fmt::format(" scale {} {} {}", k.scale->x, k.scale->y, k.scale->z);
    return out + '\n';
}

/// The keys the streaming reader reads; "declined" where it declines the
/// document, or meets an error (read_json words it).
std::string streamed(std::string_view text, const keyrot::read_options& opts, keyrot::warnings& warn) {
    std::istringstream in{std::string(text)};
    std::string out, name;
    keyrot::raw_key k;
    try {
        const auto reader = keyrot::make_key_reader(in, keyrot::format::json, opts, warn);
        while (reader->next(name, k)) out += describe(name, reader->settings(), k);
        if (reader->declined()) return "declined";
        return (reader->named() ? "named\n" : "") + out;
    } catch (const keyrot::error&) {
        return "declined";
    }
}

/// The keys read_json reads from the whole document, described as streamed() does.
class described_keys final : public keyrot::raw_key_sink {
public:
    std::string text;
    void begin_track(keyrot::raw_track header) override { track_ = std::move(header); }
    void key(keyrot::raw_key&& k) override { text += describe(track_.name, track_.settings, k); }

private:
    keyrot::raw_track track_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::ostringstream err;
    keyrot::warnings warn(err, "fuzz.json");
    keyrot::read_options opts;
    opts.source = "fuzz.json";
    const auto text = keyrot::fuzz::text(data, size);
    for (const keyrot::format f : {keyrot::format::json, keyrot::format::ndjson}) {
        try {
            std::istringstream in{std::string(text)};
            for (const auto& t : keyrot::read_document(in, f, opts, warn).tracks) keyrot::fuzz::check_track(t);
        } catch (const keyrot::error&) {
        }
    }
    // What the streaming reader takes, read_json reads as the same keys.
    if (const std::string keys = streamed(text, opts, warn); keys != "declined") {
        std::string whole;
        try {
            std::istringstream in{std::string(text)};
            described_keys read;
            whole = keyrot::read_json(in, opts, read, warn) ? "named\n" : "";
            whole += read.text;
        } catch (const keyrot::error&) {
            std::abort();
        }
        keyrot::fuzz::require(keys == whole);
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
