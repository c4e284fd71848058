#pragma once
// Mitsuba's `independent` sampler: uniform random numbers from a PCG32 stream (pcg-cpp) per pixel.
#include <cmath>
#include <cstdint>

#include <pcg_random.hpp>

#include "surfscatter/math/vec.hpp"

namespace surfscatter::render {

class Sampler {
public:
    Sampler() = default;
    Sampler(std::uint64_t seed, std::uint64_t stream) : rng_(seed, stream) {}
    double next() { return static_cast<double>(rng_()) * 0x1p-32; }  // [0, 1), exact (no libm call per number)
    Vec2 next2() {
        const double a = next();
        return {a, next()};
    }

private:
    pcg32 rng_;
};

}  // namespace surfscatter::render
