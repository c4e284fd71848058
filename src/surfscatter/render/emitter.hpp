#pragma once
// Light sources that are not shapes (emitters/*.cpp: point, spot, directional, constant, envmap). Area emitters are
// attached to shapes and sampled by the scene (scene.hpp).
#include <memory>
#include <optional>

#include "surfscatter/render/spectrum_source.hpp"
#include "surfscatter/math/vec.hpp"

namespace surfscatter::render {

struct EmitterSample {
    Vec3 wi;                   // unit direction from the shading point toward the emitter
    double distance = 0;       // to the emitter (infinity for emitters at infinity)
    SampledSpectrum radiance;  // incident radiance (area, environment), or what a delta emitter delivers: intensity
                               // / distance^2 (point, spot) or irradiance (directional)
    double pdf = 0;            // solid-angle density, or 1 for delta emitters (the emitter choice is added by Scene)
    bool delta = false;
};

class Emitter {
public:
    virtual ~Emitter() = default;
    // A direction from p toward the emitter for next-event estimation.
    virtual std::optional<EmitterSample> sample(const Vec3& p, Vec2 u, const SampledWavelengths& w) const = 0;
    // Point, spot and directional emitters cannot be hit by rays.
    virtual bool is_delta() const { return false; }
    // Emitters at infinity that rays escaping the scene see (constant, envmap): radiance arriving from `direction`
    // (world, pointing away from the scene) and the solid-angle density sample() gives that direction.
    virtual bool is_environment() const { return false; }
    virtual SampledSpectrum environment(const Vec3& /*direction*/, const SampledWavelengths& /*w*/) const {
        return SampledSpectrum(0.0);
    }
    virtual double environment_pdf(const Vec3& /*direction*/) const { return 0.0; }
};
using EmitterPtr = std::shared_ptr<const Emitter>;

// Mitsuba's constant environment emitter, for scenes built in code (emitters/constant.cpp).
EmitterPtr make_constant_emitter(SpectrumPtr radiance);

// What a point source at `position` of intensity I (W/sr per nm) delivers at p: the direction to it and I / d^2.
std::optional<EmitterSample> point_source_sample(const Vec3& position, const Vec3& p, const SampledSpectrum& intensity);

// Uniform directions on the unit sphere (density 1 / (4 pi)).
Vec3 square_to_uniform_sphere(Vec2 u);

}  // namespace surfscatter::render
