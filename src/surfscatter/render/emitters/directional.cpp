// Mitsuba's `directional` emitter: parallel light from infinity (a sun without extent).
//
// Supported: `irradiance` (spectrum or <rgb>, W/m^2 per nm on a surface facing the light; default 1), `direction`
// (<vector>, the direction the light travels) or `to_world` (light travels along its local +z); Mitsuba's default
// direction is +z.
// Differences: none.
#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

class DirectionalLight final : public Emitter {
public:
    DirectionalLight(const Vec3& direction, SpectrumPtr irradiance)
        : toward_light_(-normalize(direction)), irradiance_(std::move(irradiance)) {}

    std::optional<EmitterSample> sample(const Vec3&, Vec2, const SampledWavelengths& w) const override {
        EmitterSample s;
        s.wi = toward_light_;
        s.distance = std::numeric_limits<double>::infinity();
        s.radiance = irradiance_->eval(w);
        s.pdf = 1;
        s.delta = true;
        return s;
    }
    bool is_delta() const override { return true; }

private:
    Vec3 toward_light_;
    SpectrumPtr irradiance_;
};

}  // namespace

EmitterPtr plugins::directional(Properties& props) {
    if (props.has("direction") && props.has("to_world")) props.fail("give either direction or to_world, not both");
    Vec3 direction = props.get_transform("to_world").vector({0, 0, 1});
    if (auto d = props.get_point("direction")) direction = *d;
    if (!(direction.length() > 0)) props.fail("directional: the direction must be non-zero");
    return std::make_shared<DirectionalLight>(direction, props.get_spectrum("irradiance", true, 1.0));
}

}  // namespace surfscatter::render
