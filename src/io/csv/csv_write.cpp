// SPDX-License-Identifier: MIT
#include "io/csv/csv.hpp"

#include <fmt/format.h>

#include "ground/text.hpp"
#include "io/common/number_writer.hpp"

namespace keyrot {

void append_csv_cell(std::string& out, std::string_view text) {
    // Quoted where it would otherwise read back as something else: a comma,
    // a quote, a line break, spaces at either end (trimmed), a leading '#'
    // (a comment line, in the first column).
    if (text.find_first_of(",\"\r\n") == std::string_view::npos && trim(text) == text && !text.starts_with('#')) {
        out += text;
        return;
    }
    out += '"';
    for (char c : text) {
        if (c == '"') out += '"';
        out += c;
    }
    out += '"';
}

namespace {

class csv_writer final : public table_writer {
public:
    csv_writer(std::string& out, const table_info& info, const write_options& opts, warnings& warn)
        : out_(out), info_(info), opts_(opts), warn_(warn) {
        frame_ = info.times == time_columns::frame_and_time || (info.times == time_columns::as_given && info.any_frame);
        translation_ = info.carried.translation && opts.representation != rep::matrix4;
        scale_ = info.carried.scale;
        weights_ = info.carried.weights;
        std::vector<std::string> header;
        if (info.named) header.emplace_back("track");
        if (frame_) header.emplace_back("frame");
        header.emplace_back(info.time_name);
        for (auto c : rotation_columns(opts.representation, opts.order)) header.push_back(column_in(c, opts.angles));
        if (translation_)
            for (auto c : translation_columns) header.emplace_back(c);
        if (scale_)
            for (auto c : scale_columns) header.emplace_back(c);
        for (std::size_t i = 0; i < weights_; ++i) header.push_back(weight_column(i));
        if (info.velocity)
            for (auto c : velocity_columns) header.push_back(column_in(c, opts.angles));
        if (info.acceleration)
            for (auto c : acceleration_columns) header.push_back(column_in(c, opts.angles));
        // Only when asked: other CSV readers take the line for the header.
        if (opts.states == settings_line::always)
            fmt::format_to(std::back_inserter(out_), "{}{{{}}}\n", csv_settings_comment, settings_members(info, opts));
        fmt::format_to(std::back_inserter(out_), "{}\n", fmt::join(header, ","));
    }

    csv_writer(const csv_writer& other, std::string& out)
        : out_(out), info_(other.info_), opts_(other.opts_), warn_(other.warn_), name_(other.name_),
          frame_(other.frame_), translation_(other.translation_), scale_(other.scale_),
          weights_(other.weights_) {}

    std::unique_ptr<table_writer> row_writer(std::string& out) const override {
        return std::make_unique<csv_writer>(*this, out);
    }

    void begin_track(const std::string& name, channels) override { name_ = name; }

    void row(const table_row& s) override {
        if (info_.named) append_csv_cell(out_, name_), out_ += ',';
        row_text text(out_);
        bool first = true;
        const auto cell = [&](double v, std::optional<int> precision) {
            if (!first) text.put(',');
            first = false;
            text.number(v, precision);
        };
        // --precision rounds values, never when they are: times read back as they were.
        if (frame_) {
            if (s.frame) cell(*s.frame, std::nullopt);
            else first = false;  // (an empty cell: a key of a time alone)
        }
        cell(s.time, std::nullopt);
        const rotation_values r = row_values(s, opts_, warn_);
        for (std::size_t i = 0; i < r.size; ++i) cell(r.v[i], opts_.precision);
        const auto vector = [&](const std::optional<vec3>& v) {
            if (!v) return text.put(",,,");
            for (double x : {v->x, v->y, v->z}) cell(x, opts_.precision);
        };
        if (translation_) vector(s.translation);
        if (scale_) vector(s.scale);
        for (std::size_t i = 0; i < weights_; ++i) {
            if (i < s.weights.size()) cell(s.weights[i], opts_.precision);
            else text.put(',');
        }
        const auto rate = [&](const std::optional<vec3>& v) {
            if (!v) return text.put(",,,");
            const vec3 w = rate_values(*v, opts_);
            for (double x : {w.x, w.y, w.z}) cell(x, opts_.precision);
        };
        if (info_.velocity) rate(s.rates ? s.rates->velocity : std::nullopt);
        if (info_.acceleration) rate(s.rates ? s.rates->acceleration : std::nullopt);
        text.put('\n');
        text.flush();
    }

    void finish() override {}

private:
    std::string& out_;
    table_info info_;
    write_options opts_;
    warnings& warn_;
    std::string name_;
    bool frame_ = false, translation_ = false, scale_ = false;
    std::size_t weights_ = 0;  // columns w0 ... wN-1
};

}  // namespace

std::unique_ptr<table_writer> make_csv_writer(std::string& out, const table_info& info, const write_options& opts,
                                              warnings& warn) {
    return std::make_unique<csv_writer>(out, info, opts, warn);
}

}  // namespace keyrot
