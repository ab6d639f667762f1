#pragma once
// KEYROT_FMA_CLONES marks a hot function built twice, with the CPU's fused
// multiply-add instructions and without (x86-64's baseline has none, and
// std::fma is then a call into libm), the clone chosen when keyrot loads.
// std::fma is exact both ways and the build passes -ffp-contract=off, so the
// clones give the same bits.
#if defined(__x86_64__) && defined(__has_attribute)
#if __has_attribute(target_clones)
#define KEYROT_FMA_CLONES __attribute__((target_clones("fma", "default")))
#endif
#endif
#ifndef KEYROT_FMA_CLONES
#define KEYROT_FMA_CLONES
#endif
