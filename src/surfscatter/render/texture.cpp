#include "surfscatter/render/texture.hpp"

#include "surfscatter/spectrum/cie.hpp"

namespace surfscatter::render {

namespace {

// Y of a spectrum relative to the equal-energy white (so that a constant spectrum c gives c).
double luminance(const SpectrumSource& s) {
    const spectrum::CieTable& cie = spectrum::cie1931();
    double num = 0, den = 0;
    for (double lambda = spectrum::kSampledLambdaMin; lambda <= spectrum::kSampledLambdaMax; lambda += 1.0) {
        const double y = cie.xyz_bar(lambda).y;
        num += s.eval(lambda) * y;
        den += y;
    }
    return num / den;
}

class ConstantTexture final : public Texture {
public:
    explicit ConstantTexture(SpectrumPtr s) : spectrum_(std::move(s)), scalar_(luminance(*spectrum_)) {}
    SampledSpectrum eval(Vec2, const SampledWavelengths& w) const override { return spectrum_->eval(w); }
    double eval_1(Vec2) const override { return scalar_; }

private:
    SpectrumPtr spectrum_;
    double scalar_;
};

}  // namespace


TexturePtr make_constant_texture(SpectrumPtr spectrum) { return std::make_shared<ConstantTexture>(std::move(spectrum)); }

}  // namespace surfscatter::render
