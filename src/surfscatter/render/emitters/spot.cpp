// Mitsuba's `spot` emitter: a point light at the origin of `to_world` shining along its local +z.
//
// Supported: `intensity` (spectrum or <rgb>, W/sr per nm at the centre of the beam; default 1), `cutoff_angle`
// (degrees, default 20: black beyond it), `beam_width` (degrees, default 3/4 cutoff_angle: full intensity within it;
// between the two the intensity falls linearly with the angle, as Mitsuba), `to_world`.
// Not supported (an error): `texture` (a projected bitmap).
// Differences: none.
#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

class SpotLight final : public Emitter {
public:
    SpotLight(const Transform& to_world, SpectrumPtr intensity, double cutoff_deg, double beam_deg)
        : position_(to_world.point({0, 0, 0})), to_local_(to_world.inverse()), intensity_(std::move(intensity)),
          cutoff_(cutoff_deg * kDegree), beam_(beam_deg * kDegree), cos_cutoff_(std::cos(cutoff_)),
          cos_beam_(std::cos(beam_)) {}

    // Fraction of the central intensity emitted along local direction d.
    double falloff(const Vec3& d) const {
        const double cos_theta = normalize(d).z;
        if (cos_theta <= cos_cutoff_) return 0.0;
        if (cos_theta >= cos_beam_) return 1.0;
        return (cutoff_ - std::acos(cos_theta)) / (cutoff_ - beam_);
    }

    std::optional<EmitterSample> sample(const Vec3& p, Vec2, const SampledWavelengths& w) const override {
        const double f = falloff(to_local_.vector(p - position_));
        if (f <= 0) return std::nullopt;
        return point_source_sample(position_, p, intensity_->eval(w) * f);
    }
    bool is_delta() const override { return true; }

private:
    Vec3 position_;
    Transform to_local_;
    SpectrumPtr intensity_;
    double cutoff_, beam_, cos_cutoff_, cos_beam_;
};

}  // namespace

EmitterPtr plugins::spot(Properties& props) {
    if (props.has("texture")) props.fail_param("texture", "spot: a projected texture is not supported");
    const double cutoff = props.get_float("cutoff_angle", 20.0);
    const double beam = props.get_float("beam_width", cutoff * 3 / 4);
    if (!(cutoff > 0 && cutoff < 180)) props.fail_param("cutoff_angle", "cutoff_angle must be in (0, 180) degrees, got {}", cutoff);
    if (!(beam > 0 && beam <= cutoff)) props.fail_param("beam_width", "beam_width must be in (0, cutoff_angle], got {}", beam);
    return std::make_shared<SpotLight>(props.get_transform("to_world"), props.get_spectrum("intensity", true, 1.0), cutoff,
                                       beam);
}

}  // namespace surfscatter::render
