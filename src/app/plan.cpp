// SPDX-License-Identifier: MIT
#include "app/plan.hpp"

#include <fmt/format.h>

#include "app/usage_error.hpp"
#include "ground/warnings.hpp"
#include "io/common/output.hpp"

namespace keyrot::detail {

std::vector<std::string> input_names(const options& o) {
    if (o.inputs.empty()) return {std::string(standard_stream)};
    return o.inputs;
}

void say_failed_files(std::ostream& err, std::size_t failed, std::size_t files) {
    if (failed) print_error(err, fmt::format("{} of {} files failed", failed, files));
}

std::optional<std::string> output_path(const options& o) {
    if (!o.output || is_standard_stream(*o.output)) return std::nullopt;
    return o.output;
}

key_settings settings_of(const options& o) {
    return {o.radians ? angle_unit::radians : angle_unit::degrees, o.radians, o.euler, o.key_fps, o.key_fps.has_value(),
            o.strict};
}

read_options reading(const options& o, const std::string& source) {
    read_options ro;
    ro.source = source;
    ro.settings = settings_of(o);
    ro.order = o.order;
    ro.order_given = o.order_given;
    ro.max_bytes = o.max_bytes.value_or(default_max_bytes);
    ro.max_line_bytes = o.max_bytes.value_or(default_max_line_bytes);
    ro.animation = o.animation;
    return ro;
}

write_options writing(const options& o, const std::optional<euler_seq>& input_euler) {
    write_options w;
    w.representation = o.representation;
    w.angles = o.out_angles.value_or(o.radians ? angle_unit::radians : angle_unit::degrees);
    w.order = o.order;
    w.precision = o.precision;
    w.euler_continuous = o.euler_continuous;
    w.compact_rotations = o.compact;
    w.states = o.settings_when;
    w.commit.fsync = o.fsync;
    if (w.representation == rep::euler) {
        w.euler = o.out_euler ? o.out_euler : input_euler;
        if (!w.euler) throw usage_error("--rep euler needs an Euler sequence: expected --out-euler SEQ or --euler SEQ");
    }
    return w;
}

void check_output_format(const options& o, format out, const std::optional<std::string>& target) {
    if (o.compact && !is_gltf(out))
        throw usage_error(fmt::format("--compact stores glTF rotations as 16-bit integers, and {} has no such "
                                      "storage: expected --to gltf or glb, or -o with one of their extensions",
                                      to_string(out)));
    // As gzip does: binary bytes would garble the terminal. Naming it (-o
    // /dev/stdout) is asking for them.
    if (out == format::glb && !target && o.terminal_out)
        throw usage_error("glb is binary, and standard output is a terminal: expected -o FILE.glb, a pipe or "
                          "> FILE (--to gltf writes text; -o /dev/stdout writes glb here all the same)");
}

resample_options resampling(const options& o) {
    resample_options r;
    r.fps = o.fps;
    r.how = o.how.value_or(method::slerp);
    r.way = o.way;
    r.max_frames = o.max_frames;
    r.velocity = o.velocity, r.acceleration = o.acceleration, r.rates_frame = o.rates_frame;
    return r;
}

reduce_options reducing(const options& o) {
    reduce_options r;
    r.how = o.how.value_or(method::slerp);
    r.way = o.way;
    r.tol_deg = o.tol_deg;
    r.tol_translation = o.tol_translation;
    return r;
}

text_output::text_output(const options& o, std::ostream& out) : out_(out) {
    if (const auto file = output_path(o)) file_.emplace(*file, commit_mode{o.fsync, nullptr});
}

void text_output::write(std::string_view text) {
    pending_ += text;
    if (pending_.size() >= 1 << 16) flush();
}

void text_output::flush() {
    if (file_) file_->write(pending_);
    else write_to_stream(out_, pending_);
    pending_.clear();
}

void text_output::finish() {
    flush();
    if (file_) file_->commit();
}

void emit(const options& o, const std::string& text, std::ostream& out) {
    text_output to(o, out);
    to.write(text);
    to.finish();
}

}  // namespace keyrot::detail
