// Mitsuba's `point` emitter: an isotropic point light.
//
// Supported: `intensity` (spectrum in W/sr per nm, or <rgb> upsampled and times D65; default 1), `position`
// (<point>) or `to_world` (the position is its translation; Mitsuba accepts either).
// Differences: none.
#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

std::optional<EmitterSample> point_source_sample(const Vec3& position, const Vec3& p, const SampledSpectrum& intensity) {
    const Vec3 d = position - p;
    const double d2 = d.length_squared();
    if (!(d2 > 0)) return std::nullopt;
    EmitterSample s;
    s.distance = std::sqrt(d2);
    s.wi = d / s.distance;
    s.radiance = intensity * (1.0 / d2);
    s.pdf = 1;
    s.delta = true;
    return s;
}

namespace {

class PointLight final : public Emitter {
public:
    PointLight(const Vec3& position, SpectrumPtr intensity) : position_(position), intensity_(std::move(intensity)) {}

    std::optional<EmitterSample> sample(const Vec3& p, Vec2, const SampledWavelengths& w) const override {
        return point_source_sample(position_, p, intensity_->eval(w));
    }
    bool is_delta() const override { return true; }

private:
    Vec3 position_;
    SpectrumPtr intensity_;
};

}  // namespace

EmitterPtr plugins::point(Properties& props) {
    if (props.has("position") && props.has("to_world")) props.fail("give either position or to_world, not both");
    Vec3 position = props.get_transform("to_world").point({0, 0, 0});
    if (auto p = props.get_point("position")) position = *p;
    return std::make_shared<PointLight>(position, props.get_spectrum("intensity", true, 1.0));
}

}  // namespace surfscatter::render
