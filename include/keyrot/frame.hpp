#pragma once
// What the sampler hands the writers: one output row.
#include <optional>

#include "keyrot/quat.hpp"

namespace keyrot {

/// One output row: a resampled frame (frame = k) or a converted key.
struct sample {
    double time = 0;
    std::optional<double> frame;
    quat rotation;
    std::optional<vec3> translation;
    bool has_time = true;  ///< convert: the key gave a time (JSON writes "time" only then, if it has a frame)
};

}  // namespace keyrot
