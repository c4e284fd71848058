#include "surfscatter/bsdf/factory.hpp"

#include <cmath>
#include <limits>

#include "surfscatter/bsdf/ggx.hpp"
#include "surfscatter/bsdf/ghs.hpp"
#include "surfscatter/bsdf/ghs_ssa.hpp"
#include "surfscatter/bsdf/scatter_core.hpp"
#include "surfscatter/bsdf/two_scale.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/surface/height_map_io.hpp"
#include "surfscatter/surface/height_map_slope.hpp"
#include "surfscatter/surface/kc_fit.hpp"
#include "surfscatter/surface/psd_split.hpp"
#include "surfscatter/surface/refit.hpp"

namespace surfscatter::bsdf {

namespace {

constexpr int kRefitOrders = 13;  // orders fitted for the L m^-x power law (THEORY 2.4)

bool needs_surface(const ModelOptions& o) {
    return o.model != ModelKind::ggx || o.alpha_from != AlphaFrom::none;
}

void validate_surface(const SurfaceOptions& s) {
    switch (s.psd) {
        case PsdKind::kc:
            if (!(s.sigma > 0) || !std::isfinite(s.sigma)) fail("sigma must be > 0 um, got {}", s.sigma);
            if (!(s.corr_length > 0) || !std::isfinite(s.corr_length))
                fail("corr_length must be > 0 um, got {}", s.corr_length);
            if (!(s.gamma > 1) || !std::isfinite(s.gamma)) fail("gamma must be > 1, got {}", s.gamma);
            break;
        case PsdKind::gaussian:
            if (!(s.sigma > 0) || !std::isfinite(s.sigma)) fail("sigma must be > 0 um, got {}", s.sigma);
            if (!(s.corr_length > 0) || !std::isfinite(s.corr_length))
                fail("corr_length must be > 0 um, got {}", s.corr_length);
            break;
        case PsdKind::file:
            if (s.surface_file.empty()) fail("surface_file is empty: give a height map file");
            break;
    }
}

// KC parameters of the surface: given, or fitted to the height map (kc_fit.hpp).
surface::KCorrelation kc_of(const SurfaceOptions& s) {
    if (s.psd == PsdKind::kc) return surface::KCorrelation(s.sigma, s.corr_length, s.gamma);
    if (s.psd == PsdKind::file) {
        surface::KcFitOptions options;
        options.form = s.form;
        const auto fit = surface::fit_surface(*s.height_map, options).kc;
        return surface::KCorrelation(fit.sigma_h_um, fit.corr_length_um, fit.gamma);
    }
    fail("this option needs a K-correlation surface (psd kc or a height map), got psd {}", to_string(s.psd));
}

std::shared_ptr<const surface::RadialStatistics> statistics_of(const SurfaceOptions& s) {
    if (s.psd == PsdKind::gaussian) return std::make_shared<surface::GaussianAcv>(s.sigma, s.corr_length);
    return std::make_shared<surface::KCorrelation>(kc_of(s));
}

std::function<double(double)> ggx_alpha(const ModelOptions& o) {
    const auto constant = [](double a) { return std::function<double(double)>([a](double) { return a; }); };
    const SurfaceOptions& s = o.surface;
    switch (o.alpha_from) {
        case AlphaFrom::none: return constant(o.alpha);
        case AlphaFrom::measured:
        case AlphaFrom::smoothed: {
            const double smoothing = o.alpha_from == AlphaFrom::smoothed ? o.smoothing : 0.0;
            if (s.psd == PsdKind::file) {
                const surface::HeightMap& map = *s.height_map;
                return constant(smoothing > 0 ? surface::rms_slope_smoothed(map, smoothing, s.form)
                                              : surface::rms_slope(map, s.form));
            }
            const double no_cutoff = std::numeric_limits<double>::infinity();
            const double slope2 = statistics_of(s)->mean_square_slope(smoothing, no_cutoff);
            if (!std::isfinite(slope2) || !(slope2 > 0))
                fail("alpha_from {}: the rms slope of this PSD diverges (KC needs gamma > 3, or smoothing > 0, or a "
                     "height map)", to_string(o.alpha_from));
            return constant(std::sqrt(slope2));  // alpha_GGX = alpha_Beckmann = rms slope (THEORY 4.2)
        }
        case AlphaFrom::kc_link: {
            const double length = kc_of(s).correlation_length();
            return [length](double lambda_nm) { return kc_link_alpha(length, lambda_nm); };
        }
    }
    return constant(o.alpha);
}

GhsSettings ghs_settings(const ModelOptions& o) {
    GhsSettings settings;
    settings.fresnel = o.fresnel;
    settings.normalization = o.renormalization ? LobeNormalization::albedo : LobeNormalization::none;
    settings.relevant_roughness = o.renormalization;
    return settings;
}

}  // namespace

void validate(const ModelOptions& o) {
    if (o.model == ModelKind::ggx && o.alpha_from == AlphaFrom::none &&
        (!(o.alpha > 0) || !std::isfinite(o.alpha)))
        fail("alpha must be > 0 (or set alpha_from), got {}", o.alpha);
    if (o.alpha_from == AlphaFrom::smoothed && (!(o.smoothing > 0) || !std::isfinite(o.smoothing)))
        fail("smoothing must be > 0 um with alpha_from smoothed, got {}", o.smoothing);
    if (o.truncation == Truncation::poisson_mass && !(o.epsilon > 0 && o.epsilon < 1))
        fail("epsilon must be in (0, 1), got {}", o.epsilon);
    if (o.model == ModelKind::two_scale && (!(o.cutoff_wavelengths > 0) || !std::isfinite(o.cutoff_wavelengths)))
        fail("cutoff_wavelengths must be > 0, got {}", o.cutoff_wavelengths);
    if (o.material.empty()) fail("material is empty: give a metal name, a file or 'perfect'");
    if (needs_surface(o)) validate_surface(o.surface);
    if (o.model == ModelKind::ghs && o.method == GhsMethod::refit && o.surface.psd == PsdKind::gaussian)
        fail("method refit needs a K-correlation surface (psd kc or a height map), got psd gaussian");
}

void load_height_map(SurfaceOptions& surface) {
    if (surface.psd == PsdKind::file && !surface.height_map && !surface.surface_file.empty())
        surface.height_map =
            std::make_shared<const surface::HeightMap>(surface::read_height_map(surface.surface_file, std::nullopt));
}

std::unique_ptr<Bsdf> make_bsdf(const ModelOptions& options) {
    validate(options);
    ModelOptions o = options;
    if (needs_surface(o)) load_height_map(o.surface);
    auto material = material::Conductor::from_name(o.material);
    switch (o.model) {
        case ModelKind::ggx: return std::make_unique<GgxBsdf>(std::move(material), ggx_alpha(o));
        case ModelKind::ghs_ssa:
            return make_ghs_ssa(statistics_of(o.surface), std::move(material), o.ssa_form, o.fresnel);
        case ModelKind::ghs: {
            auto stats = statistics_of(o.surface);
            std::shared_ptr<const ScatterCore> core;
            if (o.method == GhsMethod::exact) {
                core = std::make_shared<ExactScatterCore>(stats);
            } else {
                const surface::KCorrelation kc = kc_of(o.surface);
                const double x = surface::refit_self_convolutions(kc, kRefitOrders).exponent_x;
                core = std::make_shared<RefitScatterCore>(kc, x, o.truncation, o.epsilon);
            }
            return std::make_unique<GhsBsdf>(std::move(stats), std::move(core), std::move(material), ghs_settings(o));
        }
        case ModelKind::two_scale: {
            const double zeta_c = surface::cutoff_frequency(kTwoScaleReferenceWavelength, o.cutoff_wavelengths);
            const auto split = surface::split_psd(statistics_of(o.surface), zeta_c, surface::LowPassFilter::sharp);
            // alpha = rms slope of the low-pass part, unclamped (it was floored at 1e-4, which widened the macro lobe of
            // smooth, long-correlated surfaces); a low-pass part without slope would be a mirror, not an NDF.
            const double alpha = std::sqrt(split.slope2_macro);
            if (!(alpha > 0) || !std::isfinite(alpha))
                fail("the low-pass part below {} wavelengths has rms slope {}: no macro NDF", o.cutoff_wavelengths, alpha);
            GhsSettings settings = ghs_settings(o);
            settings.name = "two_scale_micro";
            auto micro = std::make_unique<GhsBsdf>(split.micro, std::make_shared<ExactScatterCore>(split.micro),
                                                   material, settings);
            return std::make_unique<TwoScaleBsdf>(std::move(material), o.macro_ndf, alpha, std::move(micro));
        }
    }
    fail("unknown model");
}

}  // namespace surfscatter::bsdf
