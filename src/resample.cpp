#include "keyrot/resample.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>

#include "keyrot/tolerances.hpp"

namespace keyrot {

void resample(const track& t, const resample_options& opts, const std::function<void(const sample&)>& emit) {
    const rotation_curve curve(t, opts.how, opts.way);
    const translation_curve translation(t, opts.how);
    const auto& keys = t.keys;
    const double fps = opts.fps;
    const double first = std::ceil(keys.front().time * fps - tol::grid_frames);
    const double last = std::floor(keys.back().time * fps + tol::grid_frames);
    // Frame numbers must be exact integers in a double.
    constexpr double max_frame_number = 9007199254740992.0;  // 2^53
    for (const key* k : {&keys.front(), &keys.back()}) {
        const double frame = k == &keys.front() ? first : last;
        if (std::fabs(frame) >= max_frame_number)
            throw input_error(k->where, fmt::format("key time {} s is frame {:g} at {} fps: expected frames within +-2^53",
                                                    k->time, frame, fps));
    }
    if (last - first + 1 > opts.max_frames)
        throw input_error(keys.back().where,
                          fmt::format("{}keys from {} s to {} s make {:g} frames at {} fps: expected at most {:g}",
                                      t.name.empty() ? "" : fmt::format("track '{}': ", t.name), keys.front().time,
                                      keys.back().time, last - first + 1, fps, opts.max_frames));
    const double key_tol = tol::grid_frames / fps;  // seconds
    std::size_t i = 0;                              // current segment [i, i + 1]
    quat previous{};
    bool started = false;
    const auto count = static_cast<std::int64_t>(last - first + 1);  // may be 0
    for (std::int64_t n = 0; n < count; ++n) {
        const double k = first + static_cast<double>(n);
        sample s;
        s.frame = k;
        s.time = k / fps;
        while (i + 1 < keys.size() && keys[i + 1].time <= s.time + key_tol) ++i;
        if (i + 1 == keys.size() || std::fabs(s.time - keys[i].time) <= key_tol) {
            s.rotation = curve.at_key(i);
        } else {
            // keys[i].time < s.time < keys[i + 1].time here
            const double h = (s.time - keys[i].time) / (keys[i + 1].time - keys[i].time);
            s.rotation = curve.at(i, h);
        }
        if (started && dot(previous, s.rotation) < 0) s.rotation = -s.rotation;
        previous = s.rotation;
        started = true;
        s.translation = translation.at(s.time, key_tol);
        emit(s);
    }
}

}  // namespace keyrot
