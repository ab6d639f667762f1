// SPDX-License-Identifier: MIT
#pragma once
// KEYROT_FMA_CLONES marks a hot function built twice, with the CPU's fused
// multiply-add instructions and without (x86-64's baseline has none, and
// std::fma is then a call into libm), the clone chosen when keyrot loads.
// std::fma is exact both ways and the build passes -ffp-contract=off, so the
// clones give the same bits. Not under sanitizers: the choosing code runs
// before their runtimes start (ThreadSanitizer crashes there); the
// sanitizer build thus tests the plain clone, the release build the other.
#include <cmath>
#include <cstddef>
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define KEYROT_SANITIZED
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define KEYROT_SANITIZED
#endif
#if defined(__x86_64__) && defined(__has_attribute) && !defined(KEYROT_SANITIZED)
#if __has_attribute(target_clones)
#define KEYROT_FMA_CLONES __attribute__((target_clones("fma", "default")))
#endif
#endif
#ifndef KEYROT_FMA_CLONES
#define KEYROT_FMA_CLONES
#endif

namespace keyrot {

/// dot2 (keyrot/quat.hpp), forced inline so that the FMA clone of each
/// caller has it with the fused instruction (as a call of its own, it and
/// std::fma with it are the baseline CPU's: a library call a product).
template <std::size_t N>
[[gnu::always_inline]] inline double inline_dot2(const double (&x)[N], const double (&y)[N]) noexcept {
    double sum = 0, err = 0;
    for (std::size_t i = 0; i < N; ++i) {
        const double p = x[i] * y[i];
        const double p_err = std::fma(x[i], y[i], -p);
        const double t = sum + p;
        const double z = t - sum;
        err += (sum - (t - z)) + (p - z) + p_err;
        sum = t;
    }
    return sum + err;
}

}  // namespace keyrot
