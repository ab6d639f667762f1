// SPDX-License-Identifier: MIT
#include "app/compare_files.hpp"

#include <sstream>

#include "app/plan.hpp"
#include "io/common/number_writer.hpp"

namespace keyrot::detail {
surveyed_file survey_file(const options& o, const input_source& src, warnings& warn) {
    surveyed_file file{src.source(), {}, std::nullopt, {}, std::nullopt, false, 0};
    track_order order;
    std::vector<bool> float_times;  // per track: every time the shortest decimal of a 32-bit float
    const auto restart = [&] {
        file.tracks.clear(), order.clear(), file.given.clear(), float_times.clear();
        file.counted = false, file.keys = 0;
    };
    const auto each = [&](const std::string& name, const key_settings& s, key&& k) {
        const auto [at, added] = order.add(name, k, src.source());
        if (added) {
            file.tracks.emplace_back(name, s.key_fps, s.interpolation ? s.interpolation->time_rounding : 0);
            float_times.push_back(true);
            if (file.tracks.size() == 1) file.euler = s.euler;
        }
        file.tracks[at].add(k);
        if (float_times[at]) float_times[at] = shortest_decimal(static_cast<float>(k.time)) == k.time;
        file.given.insert(k.given_as);
        file.counted = file.counted || (k.frame && !k.has_time);
        ++file.keys;
    };
    file.whole = for_each_key(src, src.detect(o.from), reading(o, src.source()), warn, restart, each);
    // (a glTF file's times, as keyrot writes them out: matched within their floats' rounding)
    for (std::size_t i = 0; i < file.tracks.size(); ++i)
        if (float_times[i]) file.tracks[i].stored_as_floats();
    return file;
}

comparison_summary compare_files(const options& key_flags, const input_source& key_src, const surveyed_file& key,
                                 const options& answer_flags, const input_source& answer_src,
                                 const surveyed_file& answer,
                                 const std::function<void(const comparison_summary&)>& begin,
                                 const comparer::row_sink& row, const std::function<void(keyrot::key&)>& answer_as) {
    // (what pass 1 said is not said again)
    std::ostringstream quiet;
    warnings key_warn(quiet, key_src.source()), answer_warn(quiet, answer_src.source());
    const auto open = [](const options& o, const input_source& src, const surveyed_file& s, warnings& warn) {
        return s.whole ? key_stream(*s.whole) : key_stream(src, src.detect(o.from), reading(o, src.source()), warn);
    };
    key_stream of_key = open(key_flags, key_src, key, key_warn);
    key_stream of_answer = open(answer_flags, answer_src, answer, answer_warn);
    comparer c(key.tracks, answer.tracks, {key_flags.tol_deg, key_flags.tol_translation, key_flags.tol_velocity, key_flags.tol_acceleration},
               key_flags.extra, row);
    if (begin) begin(c.summary());
    // Read from the file whose keys do not wait for the other's: files of
    // one layout then hold a key or two each; another layout holds what it
    // must (a track that one file gives whole before the next, the other
    // interleaved), and no more.
    bool more_of_key = true, more_of_answer = true;
    std::string name;
    keyrot::key k;
    while (more_of_key || more_of_answer) {
        if (more_of_key && (!more_of_answer || c.waiting_key() <= c.waiting_answer())) {
            if ((more_of_key = of_key.next(name, k))) c.from_key(name, std::move(k));
        } else if ((more_of_answer = of_answer.next(name, k))) {
            if (answer_as) answer_as(k);
            c.from_answer(name, std::move(k));
        }
    }
    return c.finish();
}

}  // namespace keyrot::detail
