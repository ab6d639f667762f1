// SPDX-License-Identifier: MIT
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
#include <tuple>
#include <vector>

#include "ground/text.hpp"
#include "io/common/columns.hpp"
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
    key_object_reader(Value obj, const std::string& source, location at, quat_order order)
        : obj_(obj), source_(source), at_(std::move(at)), order_(order) {}

    raw_key read() {
        if (!obj_.is_object()) fail(fmt::format("expected a key object, got {}", obj_.type_name()));
        // slerp's tables name their parameter "t".
        const auto time = obj_.member("time"), t = time ? std::nullopt : obj_.member("t"), frame = obj_.member("frame");
        members m;
        m.quat = obj_.member(rotation_member(rep::quat)), m.axis = obj_.member(rotation_member(rep::axis_angle)),
        m.rotvec = obj_.member(rotation_member(rep::rotvec)), m.euler = obj_.member(rotation_member(rep::euler)),
        m.matrix = obj_.member(rotation_member(rep::matrix)), m.angle = obj_.member(angle_member);
        m.translation = obj_.member("translation"), m.scale = obj_.member("scale"), m.weights = obj_.member("weights"),
        m.velocity = obj_.member(velocity_member), m.acceleration = obj_.member(acceleration_member);
        // Counting the members read finds one that is not, without a look at each.
        const int read = !!time + !!t + !!frame + m.rotations() + !!m.angle + !!m.translation + !!m.scale +
                         !!m.weights + !!m.velocity + !!m.acceleration + obj_.member("track").has_value();
        if (obj_.size() > static_cast<std::size_t>(read) && m.rotations() == 0 && is_record()) return read_record();
        raw_key k;
        k.at = at_;
        if (obj_.size() > static_cast<std::size_t>(read)) other_members(m, k.unknown);
        if (time || t) k.time = number(time ? *time : *t, time ? "time" : "t");
        // Both, as keyrot's own frames and a table's records have: the time places the key, the frame labels it.
        if (frame) k.frame = number(*frame, "frame");
        if (!k.time && !k.frame) fail("expected a 'time' or a 'frame'");
        const int rotations = m.rotations();
        if (rotations == 0) fail("no rotation: expected one of 'quat', 'axis' and 'angle', 'rotvec', 'euler', 'matrix'");
        if (rotations > 1) fail("more than one rotation: expected exactly one of 'quat', 'axis', 'rotvec', 'euler', 'matrix'");
        if (m.angle && !m.axis) fail(fmt::format("'{}' without 'axis'", m.angle_name));
        k.angles = m.unit;

        if (m.quat) {
            k.kind = rep::quat;
            if (m.quat->is_object()) {
                const char* names[] = {"w", "x", "y", "z"};
                for (std::size_t i = 0; i < 4; ++i) {
                    const auto v = m.quat->member(names[i]);
                    if (!v) fail(fmt::format("'quat' object: missing '{}': expected w x y z", names[i]));
                    k.values[i] = number(*v, [&] { return fmt::format("quat.{}", names[i]); });
                }
            } else {
                const auto v = numbers(*m.quat, m.quat_name, 4);
                const auto wxyz = from_quat_order({v[0], v[1], v[2], v[3]}, m.order.value_or(order_));
                std::copy(wxyz.begin(), wxyz.end(), k.values.begin());
            }
        } else if (m.axis) {
            k.kind = rep::axis_angle;
            if (!m.angle) fail("'axis' without 'angle'");
            const auto v = numbers(*m.axis, "axis", 3);
            std::copy_n(v.begin(), 3, k.values.begin());
            k.values[3] = number(*m.angle, m.angle_name);
        } else if (m.rotvec) {
            k.kind = rep::rotvec;
            const auto v = numbers(*m.rotvec, m.rotvec_name, 3);
            std::copy_n(v.begin(), 3, k.values.begin());
        } else if (m.euler) {
            k.kind = rep::euler;
            const auto v = numbers(*m.euler, m.euler_name, 3);
            std::copy_n(v.begin(), 3, k.values.begin());
        } else {
            read_matrix(*m.matrix, k);
        }
        const auto vector = [this](const std::optional<Value>& member, std::string_view name) -> std::optional<vec3> {
            if (!member) return std::nullopt;
            const auto v = numbers(*member, name, 3);
            return vec3{v[0], v[1], v[2]};
        };
        k.translation = vector(m.translation, "translation");
        k.scale = vector(m.scale, "scale");
        k.rates = {vector(m.velocity, m.velocity_name), vector(m.acceleration, m.acceleration_name)};
        if (m.weights) {
            if (!m.weights->is_array() || m.weights->size() == 0)
                fail(fmt::format("'weights': expected an array of numbers, one per morph target, got {}",
                                 m.weights->is_array() ? "an empty array" : m.weights->type_name()));
            for (std::size_t i = 0; i < m.weights->size(); ++i)
                k.weights.push_back(number((*m.weights)[i], [&] { return fmt::format("weights[{}]", i); }));
        }
        return k;
    }

    /// A track's name: a string, or a number as it reads (a table's column
    /// of numbered tracks, which Miller and pandas write as numbers).
    std::string track_name(Value v) const {
        if (v.is_number()) return fmt::format("{}", v.number());
        if (!v.is_string()) fail(fmt::format("'track': expected a string, got {}", v.type_name()));
        return std::string(v.string());
    }

private:
    /// The members a key is read from, and the names they go by.
    struct members {
        std::optional<Value> quat, axis, rotvec, euler, matrix, angle, translation, scale, weights, velocity, acceleration;
        std::string_view quat_name = rotation_member(rep::quat), rotvec_name = rotation_member(rep::rotvec),
                         euler_name = rotation_member(rep::euler), angle_name = angle_member,
                         velocity_name = velocity_member, acceleration_name = acceleration_member;
        std::optional<quat_order> order;  ///< a quaternion array's, as its name says ("quat_xyzw")
        std::optional<angle_unit> unit;   ///< the angles', as their names say ("angle_rad")
        int rotations() const { return !!quat + !!axis + !!rotvec + !!euler + !!matrix; }
    };

    /// The members other than keyrot's plain names: those whose name says
    /// their unit ("angle_rad", as an NDJSON line in radians has) or a
    /// quaternion's order ("quat_xyzw"), and the first unknown one.
    void other_members(members& m, std::string& unknown) const {
        std::string_view stating;  // the first name to state a unit
        obj_.members([&](std::string_view name, Value v) {
            if (std::find(key_members.begin(), key_members.end(), name) != key_members.end()) return;
            const auto [base, unit] = split_unit(name);
            std::optional<Value>* slot = nullptr;
            std::string_view* slot_name = nullptr;
            if (name == quat_xyzw_member || name == quat_wxyz_member) {
                slot = &m.quat, slot_name = &m.quat_name;
                m.order = name == quat_xyzw_member ? quat_order::xyzw : quat_order::wxyz;
            } else if (unit && is_angle_member(base)) {
                if (m.unit && *unit != *m.unit)
                    fail(fmt::format("'{}' and '{}' state two angle units: expected one", stating, name));
                if (!m.unit) stating = name, m.unit = unit;
                for (auto [member, member_name] : {std::pair(&m.angle, &m.angle_name), std::pair(&m.rotvec, &m.rotvec_name),
                                                   std::pair(&m.euler, &m.euler_name),
                                                   std::pair(&m.velocity, &m.velocity_name),
                                                   std::pair(&m.acceleration, &m.acceleration_name)})
                    if (base == *member_name) slot = member, slot_name = member_name;
            }
            if (!slot) {
                if (unknown.empty()) unknown = name.empty() ? "\"\"" : name;
                return;
            }
            if (*slot) fail(fmt::format("both '{}' and '{}': expected one", *slot_name, name));
            *slot = v, *slot_name = name;
        });
        if (!m.unit) return;
        // A unit stated by one angle's name is stated by every angle's.
        for (const auto& [member, name] : {std::pair(&m.angle, m.angle_name), std::pair(&m.rotvec, m.rotvec_name),
                                           std::pair(&m.euler, m.euler_name), std::pair(&m.velocity, m.velocity_name),
                                           std::pair(&m.acceleration, m.acceleration_name)})
            if (*member && !split_unit(name).second)
                fail(fmt::format("'{}' states its angle unit and '{}' does not: expected every angle with its unit, "
                                 "or none",
                                 stating, name));
    }

    /// Whether the object is a table's row, its members named as CSV
    /// columns (as Miller's and pandas' records are): it has a rotation's
    /// column other than "angle", which a key's axis has beside it too.
    bool is_record() const {
        bool found = false;
        obj_.members([&](std::string_view name, Value) {
            const std::string lower = ascii_lower(name);
            found = found || (is_rotation_column(lower) && split_unit(lower).first != angle_member);
        });
        return found;
    }

    /// A table's row, read as the CSV row of the same columns would be:
    /// numbers or numbers as text, empty cells as "" or null.
    raw_key read_record() const {
        std::vector<std::string_view> names;
        std::vector<Value> values;
        obj_.members([&](std::string_view name, Value v) { names.push_back(name), values.push_back(v); });
        const column_layout cols = layout_of(names, where(source_, at_));
        struct {
            const key_object_reader& reader;
            const std::vector<Value>& values;
            const std::vector<std::string_view>& names;
            bool empty(std::size_t i) const {
                return values[i].is_null() || (values[i].is_string() && trim(values[i].string()).empty());
            }
            double number(std::size_t i, std::string_view) const {
                if (values[i].is_string())
                    if (const auto v = parse_number(trim(values[i].string()))) return *v;
                return reader.number(values[i], names[i]);
            }
            std::string text(std::size_t i) const { return reader.track_name(values[i]); }
            [[noreturn]] void fail(const std::string& message) const { reader.fail(message); }
        } cells{*this, values, names};
        raw_key k;
        k.at = at_;
        std::string track;
        read_row(cols, cells, track, k);
        for (std::size_t i = 0; i < names.size() && k.unknown.empty(); ++i)
            if (!cols.known[i] && !trim(names[i]).empty()) k.unknown = names[i];
        return k;
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
        if (*u != opts.settings.angles) conflict("angles", opts.settings.angles_given, "--radians");
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
        if (*q != opts.order) conflict("quat_order", opts.order_given, fmt::format("--quat-order {}", to_string(opts.order)));
        order = *q;
    }
    if (const auto f = obj.member("fps")) {
        if (!f->is_number() || !(f->number() > 0) || !std::isfinite(f->number()))
            throw input_error(where, "'fps': expected a positive number");
        if (opts.settings.key_fps && f->number() != *opts.settings.key_fps)
            conflict("fps", true, fmt::format("--key-fps {}", *opts.settings.key_fps));
        s.key_fps = f->number();
        s.key_fps_given = false;
    }
}

inline std::string join_path(const std::string& prefix, const std::string& item) {
    return prefix.empty() ? item : prefix + "." + item;
}

}  // namespace keyrot::detail
