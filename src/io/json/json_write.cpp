// SPDX-License-Identifier: MIT
#include "io/json/json.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "io/common/number_writer.hpp"
#include "io/json/json_members.hpp"

namespace keyrot {

using json = nlohmann::ordered_json;

namespace {

class json_writer final : public table_writer {
public:
    json_writer(std::string& out, const table_info& info, const write_options& opts, warnings& warn, bool lines)
        : out_(out), info_(info), opts_(opts), warn_(warn), lines_(lines) {
        if (lines_) {
            // A header line of the settings, which no key line has, only when asked: other NDJSON
            // readers take it for a row. The members' names say what keyrot needs.
            if (opts.states == settings_line::always) out_ += '{' + settings_members(info, opts) + "}\n";
            return;
        }
        out_ += '{' + settings_members(info, opts);
        if (info.named) out_ += ", \"tracks\": {";
    }

    json_writer(const json_writer& other, std::string& out)
        : out_(out), info_(other.info_), opts_(other.opts_), warn_(other.warn_), lines_(other.lines_),
          name_(other.name_), translation_(other.translation_), rotation_key_(other.rotation_key_),
          angle_key_(other.angle_key_), velocity_key_(other.velocity_key_), acceleration_key_(other.acceleration_key_) {}

    std::unique_ptr<table_writer> row_writer(std::string& out) const override {
        if (!lines_) return nullptr;  // commas between rows, brackets around tracks
        return std::make_unique<json_writer>(*this, out);
    }

    void begin_track(const std::string& name, channels carried) override {
        name_ = json_quote(name);
        translation_ = carried.translation && opts_.representation != rep::matrix4;
        rows_ = 0;
    }

    void row(const table_row& s) override {
        if (!lines_) {
            if (rows_++) out_ += ",\n";
            else open_track();
        }
        row_text text(out_);
        text.put('{');
        if (lines_ && info_.named) text.put("\"track\": "), text.put(name_), text.put(", ");
        if (s.frame && info_.times != time_columns::time_only)
            text.put("\"frame\": "), text.number(*s.frame, std::nullopt), text.put(", ");
        text.put('"'), text.put(info_.time_name), text.put("\": ");
        text.number(s.time, std::nullopt);  // --precision rounds values, never when they are
        write_rotation(text, row_values(s, opts_, warn_));
        if (translation_ && s.translation) {
            text.put(", \"translation\": ");
            array(text, {s.translation->x, s.translation->y, s.translation->z});
        }
        if (s.scale) text.put(", \"scale\": "), array(text, {s.scale->x, s.scale->y, s.scale->z});
        if (!s.weights.empty()) text.put(", \"weights\": "), array(text, s.weights.data(), s.weights.size());
        if (s.rates) {
            const auto rate = [&](const std::optional<vec3>& v, std::string_view key) {
                if (!v) return;
                const vec3 r = rate_values(*v, opts_);
                text.put(key), array(text, {r.x, r.y, r.z});
            };
            rate(s.rates->velocity, velocity_key_);
            rate(s.rates->acceleration, acceleration_key_);
        }
        text.put(lines_ ? "}\n" : "}");
        text.flush();
    }

    void finish() override {
        if (lines_) return;
        if (tracks_) out_ += info_.named ? "]}" : "]";
        out_ += info_.named ? "}}\n" : "}\n";
    }

private:
    /// A document's track opens at its first row: a track of no rows (a
    /// lone key off the frame grid) is left out, as CSV leaves it, not
    /// written as an empty list that reads back as no keys.
    void open_track() {
        if (tracks_++) out_ += "]}";
        if (info_.named) fmt::format_to(std::back_inserter(out_), "{}\n{}: {{", tracks_ > 1 ? "," : "", name_);
        else out_ += ", ";
        fmt::format_to(std::back_inserter(out_), "\"{}\": [\n", info_.rows_name);
    }

    void array(row_text& text, std::initializer_list<double> v) { array(text, std::data(v), v.size()); }
    void array(row_text& text, const double* v, std::size_t n) {
        text.put('[');
        for (std::size_t i = 0; i < n; ++i) {
            if (i) text.put(", ");
            text.number(v[i], opts_.precision);
        }
        text.put(']');
    }

    void write_rotation(row_text& text, const rotation_values& r) {
        const double* v = r.v.data();
        text.put(rotation_key_);
        switch (opts_.representation) {
            case rep::quat: array(text, v, 4); break;
            case rep::axis_angle:
                array(text, v, 3);
                text.put(angle_key_), text.number(v[3], opts_.precision);
                break;
            case rep::rotvec:
            case rep::euler: array(text, v, 3); break;
            case rep::matrix:
            case rep::matrix4: {
                const std::size_t n = opts_.representation == rep::matrix ? 3 : 4;
                text.put('[');
                for (std::size_t i = 0; i < n; ++i) {
                    if (i) text.put(", ");
                    array(text, v + i * n, n);
                }
                text.put(']');
                break;
            }
        }
    }

    std::string& out_;
    table_info info_;
    write_options opts_;
    warnings& warn_;
    bool lines_;
    std::string name_;
    bool translation_ = false;
    std::size_t tracks_ = 0, rows_ = 0;
    // The members' names as each row writes them (", \"quat\": "): on an NDJSON line, with the unit or
    // order they are in where it is not the default, as a JSON document states it in its fields.
    std::string key(std::string_view member) const {
        if (!lines_) return fmt::format(", \"{}\": ", member);
        return fmt::format(", \"{}\": ", member_in(member, opts_.angles, opts_.order));
    }
    std::string rotation_key_ = key(rotation_member(opts_.representation)), angle_key_ = key(angle_member),
                velocity_key_ = key(velocity_member), acceleration_key_ = key(acceleration_member);
};

}  // namespace

std::string json_quote(std::string_view text) {
    try {
        return json(text).dump();
    } catch (const json::type_error&) {
        throw input_error(fmt::format("\"{}\"", text.substr(0, 40)), "invalid UTF-8: expected text");
    }
}

std::unique_ptr<table_writer> make_json_writer(std::string& out, const table_info& info, const write_options& opts,
                                               warnings& warn, bool lines) {
    return std::make_unique<json_writer>(out, info, opts, warn, lines);
}

}  // namespace keyrot
