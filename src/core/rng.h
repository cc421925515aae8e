// Deterministic random numbers for simulation and world generation.
// Same seed, same sequence, on every platform and compiler: no std::*_distribution (their output is
// implementation-defined), only integer mixing and explicit conversions.
#pragma once
#include <cstdint>

namespace core {

// SplitMix64 finaliser: a strong 64-bit mix, also usable as a stateless hash of coordinates.
constexpr std::uint64_t mix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

// Hash of integer lattice coordinates with a seed; used for per-column decisions (trees, ore).
constexpr std::uint64_t hashCoords(std::uint64_t seed, std::int64_t x, std::int64_t y, std::int64_t z) {
    std::uint64_t h = mix64(seed);
    h = mix64(h ^ static_cast<std::uint64_t>(x));
    h = mix64(h ^ static_cast<std::uint64_t>(y));
    h = mix64(h ^ static_cast<std::uint64_t>(z));
    return h;
}

class Rng {
public:
    explicit constexpr Rng(std::uint64_t seed = 1) : m_state(seed) {}
    constexpr std::uint64_t next() {
        m_state += 0x9E3779B97F4A7C15ull;
        return mix64(m_state - 0x9E3779B97F4A7C15ull);
    }
    // Uniform in [0, 1) with 53 random bits.
    constexpr double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    constexpr double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    // Uniform integer in [0, n), n > 0 (Lemire's multiply-shift; the tiny bias is irrelevant here).
    constexpr std::uint32_t below(std::uint32_t n) { return static_cast<std::uint32_t>(((next() >> 32) * n) >> 32); }

private:
    std::uint64_t m_state;
};

} // namespace core
