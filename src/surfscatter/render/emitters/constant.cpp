// Mitsuba's `constant` emitter: the same radiance from every direction at infinity.
//
// Supported: `radiance` (spectrum, or <rgb> upsampled and times D65; default 1). Sampled uniformly over the sphere.
// Differences: none.
#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

Vec3 square_to_uniform_sphere(Vec2 u) {
    const double z = 1 - 2 * u.x, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = kTwoPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

namespace {

class ConstantEmitter final : public Emitter {
public:
    explicit ConstantEmitter(SpectrumPtr radiance) : radiance_(std::move(radiance)) {}

    std::optional<EmitterSample> sample(const Vec3&, Vec2 u, const SampledWavelengths& w) const override {
        EmitterSample s;
        s.wi = square_to_uniform_sphere(u);
        s.distance = std::numeric_limits<double>::infinity();
        s.radiance = radiance_->eval(w);
        s.pdf = 1 / (4 * kPi);
        return s;
    }
    bool is_environment() const override { return true; }
    SampledSpectrum environment(const Vec3&, const SampledWavelengths& w) const override { return radiance_->eval(w); }
    double environment_pdf(const Vec3&) const override { return 1 / (4 * kPi); }

private:
    SpectrumPtr radiance_;
};

}  // namespace

EmitterPtr make_constant_emitter(SpectrumPtr radiance) { return std::make_shared<ConstantEmitter>(std::move(radiance)); }

EmitterPtr plugins::constant(Properties& props) { return make_constant_emitter(props.get_spectrum("radiance", true, 1.0)); }

}  // namespace surfscatter::render
