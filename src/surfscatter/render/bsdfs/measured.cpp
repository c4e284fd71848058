// Mitsuba 3's `measured` BSDF: a measured (or exported: `surfscatter brdf export`) BSDF in the RGL format of Dupuy &
// Jakob 2018, `<bsdf type="measured"><string name="filename" value="file.bsdf"/></bsdf>`.
//
// Supported: `filename` (resolved against the scene file's directory), spectral files (`wavelengths` + `spectra`,
// read at each path wavelength) and RGB files (`rgb`, turned into spectra once, node by node:
// bsdf/rgl_measured.hpp). Evaluated, sampled and given a density as Mitsuba 3 does: the table direction is the
// viewer's (Mitsuba's si.wi), directions are drawn through the luminance and VNDF warps, and f = spectrum(sample) *
// ndf(m) / (4 sigma(wi)) / cos(theta_light). One-sided, reflection only (use twosided). A path wavelength outside the
// file's wavelengths is an error. Not supported (an error): anything but `filename`.
// Differences: none intended; the file's coherent specular part, if any, is a separate BSDF (docs/RENDERER.md).
#include "surfscatter/bsdf/rgl_measured.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

class MeasuredMaterial final : public Material {
public:
    explicit MeasuredMaterial(std::shared_ptr<const bsdf::RglMeasuredBsdf> model) : model_(std::move(model)) {}

    SampledSpectrum eval(const ShadingPoint&, const Vec3& wi, const Vec3& wo, const SampledWavelengths& w,
                         SampledSpectrum* pdf) const override {
        SampledSpectrum f;
        for (std::size_t k = 0; k < w.lambda.size(); ++k) f.v[k] = model_->eval(wo, wi, w.lambda[k]);
        if (pdf) *pdf = SampledSpectrum(model_->pdf(wo, wi, w.lambda[0]));
        return f;
    }

    std::optional<MaterialSample> sample(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w, double u_lobe,
                                         Vec2 u) const override {
        const auto hero = model_->sample(wo, w.lambda[0], u_lobe, u);
        if (!hero) return std::nullopt;
        MaterialSample s;
        s.wi = hero->wo;
        s.f = eval(sp, s.wi, wo, w, nullptr);
        s.pdf = SampledSpectrum(hero->pdf);
        return s;
    }

private:
    std::shared_ptr<const bsdf::RglMeasuredBsdf> model_;
};

}  // namespace

MaterialPtr plugins::measured(Properties& props) {
    const std::filesystem::path file = props.get_file("filename");
    return std::make_shared<MeasuredMaterial>(
        std::make_shared<bsdf::RglMeasuredBsdf>(bsdf::read_rgl(file), file.filename().string()));
}

}  // namespace surfscatter::render
