// SPDX-License-Identifier: MIT
#include "io/open.hpp"

#include "io/bvh/bvh_read.hpp"
#include "io/bvh/bvh_write.hpp"
#include "io/csv/csv.hpp"
#include "io/fast/read_ahead.hpp"
#include "io/fast/row_pipeline.hpp"
#include "io/gltf/gltf_read.hpp"
#include "io/gltf/gltf_write.hpp"
#include "io/json/json.hpp"
#include "io/json/json_stream.hpp"

namespace keyrot {

std::unique_ptr<key_reader> make_key_reader(std::istream& in, format f, const read_options& opts, warnings& warn,
                                            std::function<bool()> parse_ahead) {
    if (is_gltf(f)) return make_gltf_reader(in, f, opts, warn);
    if (f == format::bvh) return make_bvh_reader(in, opts);
    std::unique_ptr<line_key_reader> reader = f == format::json     ? make_json_reader(in, opts, warn)
                                              : f == format::ndjson ? make_ndjson_reader(in, opts, warn)
                                                                    : make_csv_reader(in, opts, warn);
    if (parse_ahead) return read_ahead(std::move(reader), std::move(parse_ahead));
    return reader;
}

namespace {

/// The writer of a text format, into `out`.
std::unique_ptr<table_writer> make_writer(format f, std::string& out, const table_info& info,
                                          const write_options& opts, warnings& warn) {
    if (f == format::csv) return make_csv_writer(out, info, opts, warn);
    return make_json_writer(out, info, opts, warn, f == format::ndjson);
}

/// A writer's rows through the row pipeline into chunked output.
class piped_table final : public table_output {
public:
    piped_table(format f, const std::optional<std::string>& path, std::ostream& out, const table_info& info,
                const write_options& opts, warnings& warn)
        : sink_(path, out, opts.commit), writer_(make_writer(f, sink_.text(), info, opts, warn)),
          rows_(*writer_, sink_, detail::formatting_threads()),
          sign_free_(sign_free(opts)) {}
    void begin_track(const std::string& name, channels carried, const track_interpolation&) override {
        rows_.begin_track(name, carried);
    }
    void row(const table_row& s) override { rows_.row(s); }
    void frame(const sample& s) override { rows_.frame(s); }
    /// Such frames skip the sign chain: only where the sign changes nothing written.
    arc_frame_sink* arc_frames() override { return sign_free_ ? &rows_ : nullptr; }
    void finish() override {
        rows_.finish();
        writer_->finish();
        sink_.finish();
    }

private:
    detail::chunked_output sink_;
    std::unique_ptr<table_writer> writer_;
    detail::row_pipeline rows_;
    bool sign_free_;
};

}  // namespace

std::unique_ptr<table_output> open_table(format f, const std::optional<std::string>& path, std::ostream& out,
                                         const table_info& info, const write_options& opts, warnings& warn) {
    if (is_gltf(f)) {
        // From BVH: its hierarchy as the nodes, offsets as their translations.
        std::vector<gltf_node> skeleton;
        if (opts.bvh)
            for (const bvh_node& n : opts.bvh->nodes) skeleton.push_back({n.name, n.parent, n.offset, n.joint});
        return make_gltf_table(f, path, out, opts.commit, opts.compact_rotations, opts.gltf, std::move(skeleton), warn);
    }
    if (f == format::bvh) {
        if (!opts.bvh)
            throw input_error(warn.source(), "BVH output needs a BVH input, whose hierarchy it keeps: expected a .bvh "
                                             "input, or another output format");
        // Resampled at --fps, or the input's frames as they were.
        return std::make_unique<bvh_output>(path, out, opts.bvh, info.fps, opts);
    }
    return std::make_unique<piped_table>(f, path, out, info, opts, warn);
}

bool written_at_finish(format f) { return is_gltf(f) || f == format::bvh; }

}  // namespace keyrot
