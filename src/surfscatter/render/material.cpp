#include "surfscatter/render/material.hpp"

#include <cmath>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/material/fresnel.hpp"

namespace surfscatter::render {

namespace {

constexpr int kN = spectrum::kSpectrumSamples;
double lambda_at(const SampledWavelengths& w, int i) { return w.lambda[static_cast<std::size_t>(i)]; }

Vec3 cosine_hemisphere(Vec2 u) {
    // Concentric disk mapping (Shirley-Chiu), then lift to the hemisphere.
    const double a = 2 * u.x - 1, b = 2 * u.y - 1;
    double r = 0, phi = 0;
    if (a == 0 && b == 0) return {0, 0, 1};
    if (std::abs(a) > std::abs(b)) {
        r = a;
        phi = (kPi / 4) * (b / a);
    } else {
        r = b;
        phi = kPi / 2 - (kPi / 4) * (a / b);
    }
    const double x = r * std::cos(phi), y = r * std::sin(phi);
    return {x, y, std::sqrt(std::max(0.0, 1 - x * x - y * y))};
}

class Diffuse final : public Material {
public:
    explicit Diffuse(TexturePtr reflectance) : reflectance_(std::move(reflectance)) {}

    SampledSpectrum eval(Vec2 uv, const Vec3& wi, const Vec3& wo, const SampledWavelengths& w,
                         SampledSpectrum* pdf) const override {
        if (wi.z <= 0 || wo.z <= 0) {
            if (pdf) *pdf = SampledSpectrum(0.0);
            return SampledSpectrum(0.0);
        }
        if (pdf) *pdf = SampledSpectrum(wi.z * kInvPi);
        return reflectance_->eval(uv, w) * kInvPi;
    }

    std::optional<MaterialSample> sample(Vec2 uv, const Vec3& wo, const SampledWavelengths& w, double,
                                         Vec2 u) const override {
        if (wo.z <= 0) return std::nullopt;
        MaterialSample s;
        s.wi = cosine_hemisphere(u);
        if (s.wi.z <= 0) return std::nullopt;
        s.f = reflectance_->eval(uv, w) * kInvPi;
        s.pdf = SampledSpectrum(s.wi.z * kInvPi);
        return s;
    }

private:
    TexturePtr reflectance_;
};

class SmoothConductor final : public Material {
public:
    SmoothConductor(const std::optional<material::Conductor>& conductor, const SpectrumPtr& eta, const SpectrumPtr& k,
                    TexturePtr specular)
        : specular_(std::move(specular)) {
        perfect_ = conductor && conductor->is_perfect();
        if (perfect_) return;
        // 1 nm table of the complex index: the Lorentz-Drude and tabulated models are costly per call.
        for (int i = 0; i <= kTableSize - 1; ++i) {
            const double lambda = spectrum::kSampledLambdaMin + i;
            eta_table_.push_back(conductor ? conductor->ior(lambda) : std::complex<double>(eta->eval(lambda), k->eval(lambda)));
        }
    }

    SampledSpectrum eval(Vec2, const Vec3&, const Vec3&, const SampledWavelengths&,
                         SampledSpectrum* pdf) const override {
        if (pdf) *pdf = SampledSpectrum(0.0);
        return SampledSpectrum(0.0);
    }

    std::optional<MaterialSample> sample(Vec2 uv, const Vec3& wo, const SampledWavelengths& w, double,
                                         Vec2) const override {
        if (wo.z <= 0) return std::nullopt;
        MaterialSample s;
        s.wi = reflect_about_normal(wo);
        s.delta = true;
        s.pdf = SampledSpectrum(1.0);
        s.f = specular_->eval(uv, w);
        for (int i = 0; i < kN; ++i) s.f[i] *= reflectance(wo.z, lambda_at(w, i));
        return s;
    }

    bool has_continuous_part() const override { return false; }

private:
    static constexpr int kTableSize = static_cast<int>(spectrum::kSampledLambdaMax - spectrum::kSampledLambdaMin) + 1;

    double reflectance(double cos_theta, double lambda) const {
        if (perfect_) return 1.0;
        const double x = std::clamp(lambda - spectrum::kSampledLambdaMin, 0.0, static_cast<double>(kTableSize - 1));
        const int i = std::min(static_cast<int>(x), kTableSize - 2);
        const double t = x - i;
        const std::complex<double> eta = eta_table_[static_cast<std::size_t>(i)] * (1 - t) +
                                         eta_table_[static_cast<std::size_t>(i + 1)] * t;
        return material::fresnel_conductor(cos_theta, eta);
    }

    TexturePtr specular_;
    bool perfect_ = false;
    std::vector<std::complex<double>> eta_table_;
};

class ModelMaterial final : public Material {
public:
    explicit ModelMaterial(std::shared_ptr<const bsdf::Bsdf> model) : model_(std::move(model)) {}

    SampledSpectrum eval(Vec2, const Vec3& wi, const Vec3& wo, const SampledWavelengths& w,
                         SampledSpectrum* pdf) const override {
        SampledSpectrum f;
        for (int i = 0; i < kN; ++i) {
            f[i] = model_->eval(wi, wo, lambda_at(w, i));
            if (pdf) (*pdf)[i] = model_->pdf(wo, wi, lambda_at(w, i));
        }
        return f;
    }

    std::optional<MaterialSample> sample(Vec2, const Vec3& wo, const SampledWavelengths& w, double u_lobe,
                                         Vec2 u) const override {
        // The model samples its second argument given the first; the path tracer needs the light direction given
        // the viewer's, so the sampled direction is the light's and f is evaluated as f(light, viewer).
        const auto hero = model_->sample(wo, lambda_at(w, 0), u_lobe, u);
        if (!hero || hero->wo.z <= 0) return std::nullopt;
        MaterialSample s;
        s.wi = hero->wo;
        s.delta = hero->delta;
        for (int i = 0; i < kN; ++i) {
            const double lambda = lambda_at(w, i);
            if (s.delta) {
                s.f[i] = model_->delta_reflectance(s.wi, lambda);
                s.pdf[i] = model_->delta_probability(wo, lambda);
            } else {
                s.f[i] = model_->eval(s.wi, wo, lambda);
                s.pdf[i] = i == 0 ? hero->pdf : model_->pdf(wo, s.wi, lambda);
            }
        }
        if (!(s.pdf[0] > 0)) return std::nullopt;
        return s;
    }

    bool has_continuous_part() const override { return !model_->is_pure_delta(); }

private:
    std::shared_ptr<const bsdf::Bsdf> model_;
};

class TwoSided final : public Material {
public:
    explicit TwoSided(MaterialPtr nested) : nested_(std::move(nested)) {}

    SampledSpectrum eval(Vec2 uv, const Vec3& wi, const Vec3& wo, const SampledWavelengths& w,
                         SampledSpectrum* pdf) const override {
        if (wo.z < 0) return nested_->eval(uv, flip(wi), flip(wo), w, pdf);
        return nested_->eval(uv, wi, wo, w, pdf);
    }

    std::optional<MaterialSample> sample(Vec2 uv, const Vec3& wo, const SampledWavelengths& w, double u_lobe,
                                         Vec2 u) const override {
        if (wo.z >= 0) return nested_->sample(uv, wo, w, u_lobe, u);
        auto s = nested_->sample(uv, flip(wo), w, u_lobe, u);
        if (s) s->wi = flip(s->wi);
        return s;
    }

    bool has_continuous_part() const override { return nested_->has_continuous_part(); }

private:
    static Vec3 flip(const Vec3& v) { return {v.x, v.y, -v.z}; }
    MaterialPtr nested_;
};

}  // namespace

MaterialPtr make_diffuse(TexturePtr reflectance) { return std::make_shared<Diffuse>(std::move(reflectance)); }

MaterialPtr make_smooth_conductor(const std::optional<material::Conductor>& conductor, SpectrumPtr eta, SpectrumPtr k,
                                  TexturePtr specular_reflectance) {
    if (!conductor && (!eta || !k)) fail("conductor needs a material or both eta and k");
    return std::make_shared<SmoothConductor>(conductor, eta, k, std::move(specular_reflectance));
}

MaterialPtr make_model_material(std::shared_ptr<const bsdf::Bsdf> model) {
    return std::make_shared<ModelMaterial>(std::move(model));
}

MaterialPtr make_twosided(MaterialPtr nested) { return std::make_shared<TwoSided>(std::move(nested)); }

}  // namespace surfscatter::render
