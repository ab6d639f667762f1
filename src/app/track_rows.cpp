// SPDX-License-Identifier: MIT
#include "app/track_rows.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <set>
#include <sstream>
#include <thread>
#include <utility>

#include "ground/thread_start.hpp"

namespace keyrot::detail {

std::optional<document_facts> stream_keys(key_reader& reader, row_source& source, table_output& rows, own_values own,
                                          row_counts& counts, const document_facts* known,
                                          const std::string& source_name, warnings& warn) {
    const row_sink row(rows, counts.rows, &own);
    document_facts seen;
    std::set<std::string> names;
    std::string name;
    raw_key raw;
    while (reader.next(name, raw)) {
        ++counts.keys;
        const key_settings& settings = reader.settings();
        key k = make_key(raw, settings, warn);
        const bool same_track = seen.on_last_track(name);
        if (!known && same_track) check_next(seen.tracks.back().last, k, source_name);
        if (!known && !same_track && !names.insert(name).second) return std::nullopt;
        if (!known) source.check_key(same_track ? seen.tracks.back().first : k, k, name, source_name);
        if (!same_track) {
            if (!seen.tracks.empty()) source.end_track();
            const channels carried = known ? known->tracks[seen.tracks.size()].carried : channels_of(k);
            rows.begin_track(name, carried, source.written(settings.interpolation));
            source.begin_track(name, settings.euler, settings.interpolation, carried, row);
        }
        source.add(k);
        seen.add(name, settings, std::move(k), same_track);
    }
    if (reader.declined()) return std::nullopt;
    if (!seen.tracks.empty()) source.end_track();
    seen.named = reader.named();
    return seen;
}

std::optional<document_facts> rows_apart(const std::function<std::vector<std::unique_ptr<key_reader>>()>& readers,
                                         const row_source& source, table_output& rows, const own_values& own,
                                         const std::string& source_name) {
    const unsigned cores = std::thread::hardware_concurrency();
    if (cores < 2) return std::nullopt;
    struct track_made {
        std::unique_ptr<row_source> source;
        std::unique_ptr<table_output> rows;
        std::optional<document_facts> facts;
        std::string warned;
        std::exception_ptr failure;
    };
    track_made first{source.for_track_apart(), rows.track_apart(), std::nullopt, {}, nullptr};
    if (!first.source || !first.rows) return std::nullopt;
    std::vector<std::unique_ptr<key_reader>> tracks = readers();
    if (tracks.size() < 2) return std::nullopt;
    std::vector<track_made> made(tracks.size());
    made[0] = std::move(first);
    for (std::size_t i = 1; i < made.size(); ++i)
        made[i].source = source.for_track_apart(), made[i].rows = rows.track_apart();
    std::atomic<std::size_t> next{0};
    const auto work = [&] {
        for (std::size_t i; (i = next++) < tracks.size();) {
            track_made& m = made[i];
            try {
                std::ostringstream said;
                warnings warned(said, source_name);
                row_counts counts;
                m.facts = stream_keys(*tracks[i], *m.source, *m.rows, own, counts, nullptr, source_name, warned);
                m.warned = said.str();
            } catch (...) {
                m.failure = std::current_exception();
            }
            tracks[i].reset(), m.source.reset();  // (their memory, while the other tracks are made)
        }
    };
    std::vector<std::thread> threads;
    threads.reserve(cores);  // (a thread started is never dropped for want of room)
    for (unsigned t = 1; t < std::min<std::size_t>(cores, tracks.size()); ++t) {
        std::thread thread;
        if (!try_start_thread(thread, work)) break;  // fewer threads
        threads.push_back(std::move(thread));
    }
    work();
    for (auto& t : threads) t.join();
    for (const track_made& m : made)
        if (m.failure) std::rethrow_exception(m.failure);
    if (std::any_of(made.begin(), made.end(), [](const track_made& m) { return !m.facts || !m.warned.empty(); }))
        return std::nullopt;
    document_facts seen;
    for (track_made& m : made) {
        m.rows->finish();
        seen.append(std::move(*m.facts));
    }
    return seen;
}

}  // namespace keyrot::detail
