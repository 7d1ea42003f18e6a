#pragma once
// Counter-based random numbers: a value depends only on its inputs (seed, pixel, sample, ...),
// never on thread scheduling, so renders are reproducible for any thread count.
#include <cstdint>

namespace edacrt {

/// PCG-style integer hash (Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 2020).
constexpr std::uint32_t pcg_hash(std::uint32_t v) {
    const std::uint32_t state = v * 747796405u + 2891336453u;
    const std::uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

constexpr std::uint32_t hash_combine(std::uint32_t a, std::uint32_t b) {
    return pcg_hash(a ^ (b + 0x9e3779b9u + (a << 6) + (a >> 2)));
}

/// A float in [0, 1) from the top 24 bits of a hash.
constexpr float hash_to_unit_float(std::uint32_t h) { return float(h >> 8) * (1.0f / 16777216.0f); }

}  // namespace edacrt
