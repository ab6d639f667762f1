#pragma once
// Internal to the JSON readers (json_read.cpp, json_stream.cpp): the
// fields of a key object and a document's own settings, read from a
// nlohmann-json value or a flat_json::value alike.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <optional>
#include <string>
#include <string_view>

#include "io/common/interface.hpp"
#include "io/common/layout.hpp"
#include "io/json/json_members.hpp"
#include "keyrot/error.hpp"
#include "keyrot/track.hpp"

namespace keyrot::detail {

/// A key has a dozen values, a 4x4 matrix 21: this bounds flat_json's work
/// on a hostile NDJSON line or key.
constexpr std::size_t max_key_values = 128;

/// Reads the fields of one key object: a dom_value or a flat_json::value.
template <class Value>
class key_object_reader {
public:
    key_object_reader(Value obj, const std::string& source, location at, quat_order order, bool frames_doc)
        : obj_(obj), source_(source), at_(std::move(at)), order_(order), frames_doc_(frames_doc) {}

    raw_key read() {
        if (!obj_.is_object()) fail(fmt::format("expected a key object, got {}", obj_.type_name()));
        raw_key k;
        k.at = at_;
        k.time = optional_number("time");
        // slerp's tables name their parameter "t".
        const std::optional<double> t = k.time ? std::nullopt : optional_number("t");
        if (t) k.time = t;
        k.frame = optional_number("frame");
        if (!k.time && !k.frame) fail("expected a 'time' or a 'frame'");
        if (k.time && k.frame && !frames_doc_) fail("a key has both 'time' and 'frame': expected exactly one");

        const auto quat = obj_.member(rotation_member(rep::quat)), axis = obj_.member(rotation_member(rep::axis_angle)),
                   rotvec = obj_.member(rotation_member(rep::rotvec)), euler = obj_.member(rotation_member(rep::euler)),
                   matrix = obj_.member(rotation_member(rep::matrix)), angle = obj_.member(angle_member);
        const int rotations = !!quat + !!axis + !!rotvec + !!euler + !!matrix;
        const auto translation = obj_.member("translation"), scale = obj_.member("scale"),
                   weights = obj_.member("weights"), velocity = obj_.member(velocity_member),
                   acceleration = obj_.member(acceleration_member);
        // Counting the members read finds one that is not, without a look at each.
        const int read = !!k.time + !!k.frame + rotations + !!angle + !!translation + !!scale + !!weights + !!velocity + !!acceleration +
                         obj_.member("track").has_value();
        if (obj_.size() > static_cast<std::size_t>(read)) k.unknown = first_unknown_member();
        if (rotations == 0)
            fail("no rotation: expected one of 'quat', 'axis' and 'angle', 'rotvec', 'euler', 'matrix'" + columns_hint());
        if (rotations > 1) fail("more than one rotation: expected exactly one of 'quat', 'axis', 'rotvec', 'euler', 'matrix'");
        if (angle && !axis) fail("'angle' without 'axis'");

        if (quat) {
            k.kind = rep::quat;
            if (quat->is_object()) {
                const char* names[] = {"w", "x", "y", "z"};
                for (std::size_t i = 0; i < 4; ++i) {
                    const auto v = quat->member(names[i]);
                    if (!v) fail(fmt::format("'quat' object: missing '{}': expected w x y z", names[i]));
                    k.values[i] = number(*v, [&] { return fmt::format("quat.{}", names[i]); });
                }
            } else {
                const auto v = numbers(*quat, "quat", 4);
                const auto wxyz = from_quat_order({v[0], v[1], v[2], v[3]}, order_);
                std::copy(wxyz.begin(), wxyz.end(), k.values.begin());
            }
        } else if (axis) {
            k.kind = rep::axis_angle;
            if (!angle) fail("'axis' without 'angle'");
            const auto v = numbers(*axis, "axis", 3);
            std::copy_n(v.begin(), 3, k.values.begin());
            k.values[3] = number(*angle, "angle");
        } else if (rotvec) {
            k.kind = rep::rotvec;
            const auto v = numbers(*rotvec, "rotvec", 3);
            std::copy_n(v.begin(), 3, k.values.begin());
        } else if (euler) {
            k.kind = rep::euler;
            const auto v = numbers(*euler, "euler", 3);
            std::copy_n(v.begin(), 3, k.values.begin());
        } else {
            read_matrix(*matrix, k);
        }
        const auto vector = [this](const std::optional<Value>& member, const char* name) -> std::optional<vec3> {
            if (!member) return std::nullopt;
            const auto v = numbers(*member, name, 3);
            return vec3{v[0], v[1], v[2]};
        };
        k.translation = vector(translation, "translation");
        k.scale = vector(scale, "scale");
        k.rates = {vector(velocity, velocity_member.data()), vector(acceleration, acceleration_member.data())};
        if (weights) {
            if (!weights->is_array() || weights->size() == 0)
                fail(fmt::format("'weights': expected an array of numbers, one per morph target, got {}",
                                 weights->is_array() ? "an empty array" : weights->type_name()));
            for (std::size_t i = 0; i < weights->size(); ++i)
                k.weights.push_back(number((*weights)[i], [&] { return fmt::format("weights[{}]", i); }));
        }
        return k;
    }

private:
    std::string first_unknown_member() const {
        std::string name;
        obj_.members([&](std::string_view member, Value) {
            if (name.empty() && std::find(key_members.begin(), key_members.end(), member) == key_members.end())
                name = member.empty() ? "\"\"" : member;
        });
        return name;
    }

    /// A key without a rotation member whose fields are a rotation's CSV
    /// columns (pandas' to_json writes a table's rows so): what to write
    /// instead. Empty for other keys.
    std::string columns_hint() const {
        for (const auto& r : names_of<rep>) {
            const auto columns = rotation_columns(r.value, quat_order::wxyz);
            if (!obj_.member(columns.front())) continue;
            return fmt::format(", got '{}', a CSV column: write the table as CSV (pandas: to_csv), or the rotation as "
                               "'{}'{} (keyrot help formats)",
                               columns.front(), rotation_member(r.value), r.value == rep::axis_angle ? " and 'angle'" : "");
        }
        return "";
    }

    [[noreturn]] void fail(const std::string& message) const { throw input_error(where(source_, at_), message); }

    /// Messages name the field: `field` is its name, or a callable that
    /// spells the name out ("quat[2]"), called only when there is an error.
    double number(Value j, const std::invocable auto& field) const {
        if (!j.is_number())
            fail(fmt::format("'{}': expected a number, got {}{}", field(), j.type_name(),
                             j.is_string() ? fmt::format(" \"{}\"", j.string().substr(0, 40)) : ""));
        const double v = j.number();
        if (!std::isfinite(v)) fail(fmt::format("'{}': expected a finite number, got {}", field(), v));
        return v;
    }
    double number(Value j, std::string_view field) const {
        return number(j, [field] { return field; });
    }

    std::optional<double> optional_number(std::string_view field) const {
        if (const auto j = obj_.member(field)) return number(*j, field);
        return std::nullopt;
    }

    /// The n (at most 4) numbers of an array field, in the first n places.
    std::array<double, 4> numbers(Value j, const std::invocable auto& field, std::size_t n) const {
        if (!j.is_array() || j.size() != n)
            fail(fmt::format("'{}': expected an array of {} numbers, got {}", field(), n,
                             j.is_array() ? fmt::format("{} elements", j.size()) : std::string(j.type_name())));
        std::array<double, 4> out{};
        for (std::size_t i = 0; i < n; ++i) out[i] = number(j[i], [&] { return fmt::format("{}[{}]", field(), i); });
        return out;
    }
    std::array<double, 4> numbers(Value j, std::string_view field, std::size_t n) const {
        return numbers(j, [field] { return field; }, n);
    }

    void read_matrix(Value m, raw_key& k) const {
        if (!m.is_array() || (m.size() != 3 && m.size() != 4))
            fail(fmt::format("'matrix': expected 3 or 4 rows, got {}",
                             m.is_array() ? fmt::format("{} rows", m.size()) : std::string(m.type_name())));
        const std::size_t n = m.size();
        k.kind = n == 4 ? rep::matrix4 : rep::matrix;
        for (std::size_t r = 0; r < n; ++r) {
            const auto row = numbers(m[r], [r] { return fmt::format("matrix[{}]", r); }, n);
            std::copy_n(row.begin(), n, k.values.begin() + static_cast<std::ptrdiff_t>(r * n));
        }
    }

    Value obj_;
    const std::string& source_;
    location at_;
    quat_order order_;
    bool frames_doc_;
};

/// Which members an object that states settings may have besides them.
enum class settings_object {
    document,  ///< "keys", "frames" or "tracks"
    track,     ///< "keys" or "frames"
    header,    ///< none: an NDJSON header line, a CSV "# keyrot" line
};

/// Fields keyrot writes that say how a document was made, and that change
/// nothing on reading.
inline bool descriptive_field(std::string_view name) { return name == "method" || name == "rep"; }

/// Applies a document's own fields ("angles", "euler", "quat_order", "fps")
/// over the settings it inherits. Where a flag the user gave says
/// otherwise, the document wins and says so; a field keyrot does not know
/// is reported by unknown_field.
template <class Value>
void apply_fields(Value obj, key_settings& s, quat_order& order, const std::string& where, settings_object kind,
                  const read_options& opts, warnings& warn) {
    if (!obj.is_object()) return;
    obj.members([&](std::string_view name, Value) {
        const bool known = name == "angles" || name == "euler" || name == "quat_order" || name == "fps" ||
                           descriptive_field(name) ||
                           (kind != settings_object::header && (name == "keys" || name == "frames")) ||
                           (kind == settings_object::document && name == "tracks");
        if (!known) unknown_field(name, where, s, warn);
    });
    auto text = [&](const char* field) -> std::optional<std::string> {
        const auto v = obj.member(field);
        if (!v) return std::nullopt;
        if (!v->is_string()) throw input_error(where, fmt::format("'{}': expected a string, got {}", field, v->type_name()));
        return std::string(v->string());
    };
    const auto conflict = [&](const char* field, bool given, const std::string& flag) {
        if (given) warn.once(fmt::format("conflict {}", field), fmt::format("the file's '{}' is used, not {}", field, flag));
    };
    if (auto a = text("angles")) {
        const auto u = parse<angle_unit>(*a);
        if (!u) throw input_error(where, fmt::format("'angles': expected \"degrees\" or \"radians\", got \"{}\"", excerpt(*a)));
        if (*u != opts.settings.angles) conflict("angles", opts.given.angles, "--radians");
        s.angles = *u;
    }
    if (auto e = text("euler")) {
        const auto seq = parse_euler_seq(*e);
        if (!seq)
            throw input_error(where, fmt::format("'euler': expected a sequence like \"ZYX\" or \"xyz\", got \"{}\"", excerpt(*e)));
        if (opts.settings.euler && seq->name != opts.settings.euler->name)
            conflict("euler", true, "--euler " + opts.settings.euler->name);
        s.euler = seq;
    }
    if (auto o = text("quat_order")) {
        const auto q = parse<quat_order>(*o);
        if (!q) throw input_error(where, fmt::format("'quat_order': expected \"wxyz\" or \"xyzw\", got \"{}\"", excerpt(*o)));
        if (*q != opts.order) conflict("quat_order", opts.given.order, fmt::format("--quat-order {}", to_string(opts.order)));
        order = *q;
    }
    if (const auto f = obj.member("fps")) {
        if (!f->is_number() || !(f->number() > 0) || !std::isfinite(f->number()))
            throw input_error(where, "'fps': expected a positive number");
        if (opts.settings.key_fps && f->number() != *opts.settings.key_fps)
            conflict("fps", true, fmt::format("--key-fps {}", *opts.settings.key_fps));
        s.key_fps = f->number();
    }
}

inline std::string join_path(const std::string& prefix, const std::string& item) {
    return prefix.empty() ? item : prefix + "." + item;
}

}  // namespace keyrot::detail
