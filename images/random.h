// Seeded random numbers whose sequence is fixed by this file alone. std::mt19937 is specified,
// but std::uniform_real_distribution is not (its output differs between standard libraries), so
// generated test content would not be byte-identical across platforms. SplitMix64 (Steele et al.,
// "Fast splittable pseudorandom number generators", 2014) is tiny and statistically sound for this.
#pragma once

#include <cstdint>

namespace kdop {

class Random {
public:
    explicit Random(std::uint64_t seed) : state_(seed) {}

    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }

    // Uniform in [0, 1), from the top 53 bits.
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

private:
    std::uint64_t state_;
};

// A hash of lattice coordinates and a seed to [0, 1): stateless randomness for noise functions.
inline double hash_to_unit(std::int64_t x, std::int64_t y, std::uint64_t seed) {
    Random r(seed ^ (static_cast<std::uint64_t>(x) * 0x8cb92ba72f3d8dd7ull) ^
             (static_cast<std::uint64_t>(y) * 0xd6e8feb86659fd93ull));
    return r.uniform();
}

} // namespace kdop
