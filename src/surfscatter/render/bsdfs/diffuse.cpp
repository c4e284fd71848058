// Mitsuba's `diffuse` BSDF: Lambertian reflection, one-sided.
//
// Supported: `reflectance` (value, spectrum, <rgb> or texture; default 0.5). Sampled by the cosine-weighted
// hemisphere (concentric mapping).
// Differences: none.
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

class Diffuse final : public Material {
public:
    explicit Diffuse(TexturePtr reflectance) : reflectance_(std::move(reflectance)) {}

    SampledSpectrum eval(const ShadingPoint& sp, const Vec3& wi, const Vec3& wo, const SampledWavelengths& w,
                         SampledSpectrum* pdf) const override {
        if (wi.z <= 0 || wo.z <= 0) {
            if (pdf) *pdf = SampledSpectrum(0.0);
            return SampledSpectrum(0.0);
        }
        if (pdf) *pdf = SampledSpectrum(wi.z * kInvPi);
        return reflectance_->eval(sp.uv, w) * kInvPi;
    }

    std::optional<MaterialSample> sample(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w, double,
                                         Vec2 u) const override {
        if (wo.z <= 0) return std::nullopt;
        MaterialSample s;
        s.wi = square_to_cosine_hemisphere(u);
        if (s.wi.z <= 0) return std::nullopt;
        s.f = reflectance_->eval(sp.uv, w) * kInvPi;
        s.pdf = SampledSpectrum(s.wi.z * kInvPi);
        return s;
    }

private:
    TexturePtr reflectance_;
};

}  // namespace

MaterialPtr make_diffuse(TexturePtr reflectance) { return std::make_shared<Diffuse>(std::move(reflectance)); }

MaterialPtr plugins::diffuse(Properties& props) { return make_diffuse(props.get_texture("reflectance", 0.5)); }

}  // namespace surfscatter::render
