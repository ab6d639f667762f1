// SPDX-License-Identifier: MIT
#include "app/compare_hints.hpp"

#include <fmt/format.h>

#include <array>
#include <functional>
#include <sstream>
#include <string_view>

#include "ground/text.hpp"

namespace keyrot::detail {

namespace {

/// The answers keyrot looks at for a likely cause: no more keys than a
/// homework file, as each reading of another way costs a reading of it.
constexpr std::size_t hint_keys = 100000;

/// The rate a file's frames count at, and why: "30 fps (as it states)",
/// "24 fps (the default; it states no rate)"; "" for a file of no frames.
std::string frame_rate_of(const surveyed_file& f) {
    for (const track_survey& t : f.tracks) {
        if (!t.any_frame()) continue;
        const std::string rate = fmt::format("{:g} fps", t.counted_rate());
        if (t.rate_implied()) return rate + " (by their times)";
        return rate + (t.rate_stated() ? " (as it states)" : " (the default; it states no rate)");
    }
    return "";
}

/// Another reading of an answer: the flags it is read with, what a key is
/// made of otherwise, and how the hint words it.
struct reading {
    options flags;
    std::function<void(keyrot::key&)> key_as = nullptr;
    std::string how;
};

/// A quaternion key's values taken in another order: `order` gives, for
/// (w, x, y, z), where each is among the values as read.
std::function<void(keyrot::key&)> quaternion_as(std::array<std::size_t, 4> order) {
    return [order](keyrot::key& k) {
        if (k.given_as != rep::quat || !k.given) return;
        const auto& v = k.given->values;
        k.rotation = normalized(quat{v[order[0]], v[order[1]], v[order[2]], v[order[3]]});
    };
}

}  // namespace

std::vector<std::pair<std::string, std::string>> tracks_named_in_another_case(const comparison_summary& c) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const std::string& missing : c.missing_tracks)
        for (const std::string& extra : c.extra_tracks)
            if (ascii_lower(missing) == ascii_lower(extra)) out.emplace_back(missing, extra);
    return out;
}

std::string likely_cause(const options& o, const input_source& key_src, const surveyed_file& key,
                         const input_source& src, const surveyed_file& answer, const comparison_summary& c) {
    if (const auto cased = tracks_named_in_another_case(c); !cased.empty())
        return fmt::format("the answer's track '{}' is the key's '{}' in another case: expected the key's track names",
                           cased.front().second, cased.front().first);
    if (c.missing > 0 && c.extra > 0 && (key.counted || answer.counted)) {
        std::vector<std::string> rates;
        for (const auto& [who, file] : {std::pair("the key", &key), std::pair("the answer", &answer)})
            if (const std::string rate = frame_rate_of(*file); !rate.empty())
                rates.push_back(fmt::format("{} counts its frames at {}", who, rate));
        return fmt::format("rows missing and extra: {}; --key-fps RATE reads the frames of a file that states no "
                           "rate at another",
                           fmt::join(rates, ", "));
    }
    const bool some_differ = c.worst && *c.worst->angle_deg > o.tol_deg;
    if (!some_differ || answer.keys > hint_keys) return "";
    const auto& given = answer.given;
    std::vector<reading> readings;
    if (given.contains(rep::axis_angle) || given.contains(rep::rotvec) || given.contains(rep::euler)) {
        options other = o;
        other.radians = !o.radians;
        readings.push_back({other, nullptr, o.radians ? "read as degrees (without --radians)" : "read as radians (--radians)"});
    }
    if (given.contains(rep::quat)) {
        if (src.detect(o.from) == format::csv) {
            // CSV names its columns: where a header names them in the other order than the values are in
            readings.push_back({o, quaternion_as({3, 0, 1, 2}),
                                "read with its values under qw,qx,qy,qz as x, y, z, w: its header should read "
                                "qx,qy,qz,qw"});
            readings.push_back({o, quaternion_as({1, 2, 3, 0}),
                                "read with its values under qx,qy,qz,qw as w, x, y, z: its header should read "
                                "qw,qx,qy,qz"});
        } else {
            options other = o;
            other.order = o.order == quat_order::wxyz ? quat_order::xyzw : quat_order::wxyz;
            other.order_given = true;
            readings.push_back({other, nullptr, fmt::format("read with --quat-order {}", to_string(other.order))});
        }
    }
    if (given.contains(rep::euler))
        for (const std::string_view axes : {"ZYX", "XYZ", "ZXY", "YXZ", "XZY", "YZX", "ZXZ", "ZYZ", "XYX", "XZX",
                                            "YXY", "YZY", "xyz", "zyx", "zxy", "yxz", "xzy", "yzx", "zxz", "zyz",
                                            "xyx", "xzx", "yxy", "yzy"}) {
            const euler_seq seq = *parse_euler_seq(axes);
            if (answer.euler && seq.name == answer.euler->name) continue;
            options other = o;
            other.euler = seq;
            readings.push_back({other, nullptr, fmt::format("read with --euler {}", axes)});
        }
    for (const reading& r : readings) {
        try {
            // (a document held whole holds keys made the first way: it is read again)
            std::ostringstream quiet;
            warnings warn(quiet, src.source());
            const std::optional<surveyed_file> again =
                answer.whole && !r.key_as ? std::optional(survey_file(r.flags, src, warn)) : std::nullopt;
            if (compare_files(o, key_src, key, r.flags, src, again ? *again : answer, nullptr, nullptr, r.key_as)
                    .failed == 0)
                return fmt::format("every row is within tolerance when the answer is {}", r.how);
        } catch (const error&) {  // that reading is not a cause
        }
    }
    return "";
}

}  // namespace keyrot::detail
