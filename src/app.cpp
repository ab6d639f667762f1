#include "keyrot/app.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#include "keyrot/output.hpp"
#include "keyrot/resample.hpp"

namespace keyrot {
namespace {

std::string read_stream(std::istream& in) {
    std::ostringstream buf;
    buf << in.rdbuf();
    return std::move(buf).str();
}

std::string read_file(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw error(fmt::format("cannot read '{}': it is a directory", path));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw error(fmt::format("cannot read '{}': {}", path, std::strerror(errno)));
    return read_stream(in);
}

write_options output_settings(const options& o, const std::vector<track>& tracks) {
    write_options w;
    w.representation = o.representation;
    w.angles = o.out_angles.value_or(o.radians ? angle_unit::radians : angle_unit::degrees);
    w.order = o.order;
    w.precision = o.precision;
    if (w.representation == rep::euler) {
        // --out-euler, else the input's sequence (--euler or the document's own).
        w.euler = o.out_euler ? o.out_euler : tracks.front().euler;
        if (!w.euler) throw usage_error("--rep euler needs an Euler sequence: expected --out-euler SEQ or --euler SEQ");
    }
    return w;
}

bool has_translation(const track& t) {
    for (const key& k : t.keys)
        if (k.translation) return true;
    return false;
}

/// Reads one input document and returns the text of its output.
std::string process(const options& o, std::string_view text, format in_fmt, format out_fmt, warnings& warn) {
    read_options ro;
    ro.source = warn.source();
    ro.settings = {o.radians ? angle_unit::radians : angle_unit::degrees, o.euler, o.key_fps.value_or(o.fps), o.strict};
    ro.order = o.order;
    const raw_document doc = read_document(text, in_fmt, ro, warn);
    std::vector<track> tracks;
    tracks.reserve(doc.tracks.size());
    for (const raw_track& raw : doc.tracks) tracks.push_back(make_track(raw, warn));

    table_info info;
    info.named = doc.named;
    for (const track& t : tracks) info.translation = info.translation || has_translation(t);
    if (o.cmd == command::resample) {
        info.fps = o.fps;
        info.how = o.how;
    } else {
        info.times = time_columns::as_given;
        info.rows_name = "keys";
        info.all_frames = true;
        for (const track& t : tracks)
            for (const key& k : t.keys) info.all_frames = info.all_frames && k.frame.has_value();
    }

    std::string out;
    const auto writer = make_writer(out_fmt, out, info, output_settings(o, tracks), warn);
    const resample_options ropts{o.fps, o.how, o.way};
    for (const track& t : tracks) {
        writer->begin_track(t.name, has_translation(t));
        if (o.cmd == command::resample) {
            resample(t, ropts, warn.source(), [&](const sample& s) { writer->row(s); });
        } else {
            for (const key& k : t.keys) writer->row(sample{k.time, k.frame, k.rotation, k.translation});
        }
    }
    writer->finish();
    return out;
}

}  // namespace

int run(const options& o, std::istream& in, std::ostream& out, std::ostream& err) {
    const std::vector<std::string> inputs = o.inputs.empty() ? std::vector<std::string>{"-"} : o.inputs;
    if (inputs.size() > 1 && !o.output_dir)
        throw usage_error("several input files need --output-dir DIR");
    if (o.output_dir && o.output) throw usage_error("-o and --output-dir: expected one of them");
    if (o.output_dir) {
        std::error_code ec;
        std::filesystem::create_directories(*o.output_dir, ec);
        if (ec) throw error(fmt::format("cannot create directory '{}': {}", *o.output_dir, ec.message()));
    }

    int status = 0;
    for (const std::string& input : inputs) {
        try {
            const bool from_stdin = input == "-";
            if (from_stdin && o.output_dir) throw usage_error("standard input ('-') cannot be used with --output-dir");
            const std::string text = from_stdin ? read_stream(in) : read_file(input);
            warnings warn(err, from_stdin ? "<stdin>" : input);
            const format in_fmt = o.from ? *o.from : format_of_path(input).value_or(sniff_format(text));
            std::optional<std::string> target;
            format out_fmt = o.to.value_or(in_fmt);
            if (o.output_dir) {
                std::filesystem::path name = std::filesystem::path(input).filename();
                name.replace_extension(to_string(out_fmt));
                target = (std::filesystem::path(*o.output_dir) / name).string();
            } else if (o.output && *o.output != "-") {
                target = *o.output;
                if (!o.to) out_fmt = format_of_path(*target).value_or(in_fmt);
            }
            const std::string result = process(o, text, in_fmt, out_fmt, warn);
            if (target) {
                write_file_atomically(*target, result);
            } else {
                out << result;
                out.flush();
            }
        } catch (const usage_error&) {
            throw;
        } catch (const error& e) {
            err << "keyrot: " << e.what() << '\n';
            status = 2;
        }
    }
    return status;
}

}  // namespace keyrot
