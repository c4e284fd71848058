#include "surfscatter/surface/kc_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include <Eigen/Core>
#include <unsupported/Eigen/NonLinearOptimization>
#include <unsupported/Eigen/NumericalDiff>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/height_map_slope.hpp"
#include "surfscatter/surface/least_squares_functor.hpp"
#include "surfscatter/surface/map_statistics.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface {

namespace {

struct RingData {
    std::vector<double> zeta, log_psd, weight, log_bias;
    bool profile = false;  // a profile's 1-D PSD: the KC's profile PSD is the model
};

// Residuals sqrt(nu_i) (ln Pbar_i - b_i - ln sigma^2 - ln P-hat_i) with ln sigma^2 profiled out; returns ln sigma^2.
double profiled_residuals(const RingData& data, double log_l, double log_gm1, Eigen::VectorXd& residuals) {
    const std::size_t n = data.zeta.size();
    residuals.resize(static_cast<Eigen::Index>(n));
    // Levenberg-Marquardt may step far outside the search box; there the cost is held at the box's edge (slightly
    // beyond it, so the bound test below reports such a fit) instead of building an invalid KC model.
    const double lo = std::log(kKcGammaMinusOneMin) - 0.5, hi = std::log(kKcGammaMinusOneMax) + 0.5;
    const KCorrelation model(1.0, std::exp(std::clamp(log_l, -200.0, 200.0)), 1.0 + std::exp(std::clamp(log_gm1, lo, hi)));
    double sum_w = 0.0, sum_wd = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double unit = data.profile ? model.profile_psd_unit(data.zeta[i]) : model.psd_unit(data.zeta[i]);
        const double d = data.log_psd[i] - data.log_bias[i] - std::log(unit);
        residuals[static_cast<Eigen::Index>(i)] = d;
        sum_w += data.weight[i];
        sum_wd += data.weight[i] * d;
    }
    const double log_variance = sum_wd / sum_w;
    for (std::size_t i = 0; i < n; ++i) {
        const auto k = static_cast<Eigen::Index>(i);
        residuals[k] = std::sqrt(data.weight[i]) * (residuals[k] - log_variance);
    }
    return log_variance;
}

struct LogResidualFunctor : DynamicLeastSquaresFunctor {
    const RingData* data;
    int inputs() const { return 2; }
    int values() const { return static_cast<int>(data->zeta.size()); }
    int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& residuals) const {
        profiled_residuals(*data, x[0], x[1], residuals);
        return 0;
    }
};

}  // namespace

const char* search_box_end(double value, double lo, double hi) {
    if (value < lo + 0.02 * (hi - lo)) return "lower";
    if (value > hi - 0.02 * (hi - lo)) return "upper";
    return nullptr;
}

double nyquist_zeta(const heightmap::HeightMap& map) { return kPi / std::max(map.spacing_x(), map.spacing_y()); }

KcFit fit_kc(const RadialPsd& radial, double nyquist, const KcFitOptions& options) {
    if (options.min_ring < 1) fail("KC fit: the first ring must be >= 1, got {}", options.min_ring);
    if (!(options.max_nyquist_fraction > 0.0 && options.max_nyquist_fraction <= 1.0))
        fail("KC fit: the upper band limit must be a fraction of Nyquist in (0, 1], got {}",
             options.max_nyquist_fraction);
    KcFit fit;
    fit.zeta_min = (static_cast<double>(options.min_ring) - 0.5) * radial.dzeta;
    fit.zeta_max = options.max_nyquist_fraction * nyquist;

    RingData data;
    data.profile = options.profile;
    for (std::size_t i = 0; i < radial.zeta.size(); ++i) {
        if (radial.zeta[i] < fit.zeta_min || radial.zeta[i] > fit.zeta_max) continue;
        if (!(radial.psd[i] > 0.0)) continue;  // exactly zero power (e.g. a synthetic band edge) has no log
        const double nu = effective_samples(radial.window, radial.count[i], radial.valid_weight);
        data.zeta.push_back(radial.zeta[i]);
        data.log_psd.push_back(std::log(radial.psd[i]));
        data.weight.push_back(nu);
        data.log_bias.push_back(-1.0 / (2.0 * nu) - 1.0 / (12.0 * nu * nu));
    }
    fit.rings = data.zeta.size();
    if (fit.rings < 8)
        fail("KC fit: only {} PSD rings between {} and {} rad/um; the map is too small to fit (need >= 8)",
             fit.rings, fit.zeta_min, fit.zeta_max);

    // The knee 1/L must be resolvable: search L from 1/(4 zeta_max) to 4/zeta_min.
    const double log_l_min = std::log(0.25 / fit.zeta_max), log_l_max = std::log(4.0 / fit.zeta_min);
    const double log_g_min = std::log(kKcGammaMinusOneMin), log_g_max = std::log(kKcGammaMinusOneMax);
    Eigen::VectorXd residuals;
    Eigen::VectorXd best(2);
    double best_cost = std::numeric_limits<double>::infinity();
    constexpr int kGridL = 48, kGridGamma = 32;
    for (int a = 0; a <= kGridL; ++a)
        for (int b = 0; b <= kGridGamma; ++b) {
            const double log_l = log_l_min + (log_l_max - log_l_min) * a / kGridL;
            const double log_g = log_g_min + (log_g_max - log_g_min) * b / kGridGamma;
            profiled_residuals(data, log_l, log_g, residuals);
            const double cost = residuals.squaredNorm();
            if (cost < best_cost) {
                best_cost = cost;
                best << log_l, log_g;
            }
        }

    LogResidualFunctor functor{{}, &data};
    Eigen::NumericalDiff<LogResidualFunctor, Eigen::Central> numerical(functor);
    Eigen::LevenbergMarquardt<Eigen::NumericalDiff<LogResidualFunctor, Eigen::Central>> solver(numerical);
    solver.parameters.xtol = 1e-12;
    solver.parameters.ftol = 1e-14;
    solver.parameters.maxfev = 2000;
    // The polish stays inside the searched box: a valley running out of it (no knee in the band) would otherwise
    // carry L_c to any size.
    const Eigen::VectorXd grid_best = best;
    solver.minimize(best);
    if (!(best.allFinite() && best[0] >= log_l_min && best[0] <= log_l_max && best[1] >= log_g_min &&
          best[1] <= log_g_max))
        best = grid_best;

    const double log_variance = profiled_residuals(data, best[0], best[1], residuals);
    const double l = std::exp(best[0]), gamma = 1.0 + std::exp(best[1]);
    double sum_w = 0.0;
    for (double w : data.weight) sum_w += w;
    fit.sigma_h_um = std::exp(0.5 * log_variance);
    fit.corr_length_um = l;
    fit.gamma = gamma;
    fit.log_residual_rms = std::sqrt(residuals.squaredNorm() / sum_w);
    fit.statistical_floor = std::sqrt(static_cast<double>(fit.rings) / sum_w);

    const std::string band = fmt::format("the PSD between {:.4g} and {:.4g} rad/um ({} rings)", fit.zeta_min,
                                         fit.zeta_max, fit.rings);
    const char* instead = options.profile ? "the areal models take a profile's statistics from this fit"
                                          : "use --psd measured for the map's own spectrum";
    const std::string misfit = fmt::format("misfit log_residual_rms {:.3g} against a statistical floor of {:.3g}",
                                           fit.log_residual_rms, fit.statistical_floor);
    if (const char* end = search_box_end(best[0], log_l_min, log_l_max))
        fit.failure = fmt::format(
            "KC fit: no KC correlation length fits {}: L_c was searched from {:.4g} to {:.4g} um (1/(4 zeta_max) to "
            "4/zeta_min) and the best attempt lies at the {} end (L_c = {:.4g} um, gamma = {:.4g}, {}): the PSD has "
            "no KC knee inside the band; {}",
            band, std::exp(log_l_min), std::exp(log_l_max), end, l, gamma, misfit, instead);
    else if (const char* end = search_box_end(best[1], log_g_min, log_g_max))
        fit.failure = fmt::format(
            "KC fit: gamma is not resolved by {}: gamma was searched from {:.4g} to {:.4g} and the best attempt lies "
            "at the {} end (gamma = {:.4g}, L_c = {:.4g} um, {}; a PSD falling faster than any power law, e.g. "
            "Gaussian, has no KC gamma); {}",
            band, 1.0 + kKcGammaMinusOneMin, 1.0 + kKcGammaMinusOneMax, end, gamma, l, misfit, instead);
    return fit;
}

void require_resolved(const KcFit& fit) {
    if (!fit.failure.empty()) fail("{}", fit.failure);
}

SurfaceFit fit_surface(const heightmap::HeightMap& map, const KcFitOptions& options) {
    heightmap::require_valid_fraction(map, heightmap::kMinFitValidFraction, "a KC fit");
    SurfaceFit result;
    const heightmap::HeightMap flat = heightmap::remove_form(map, options.form);
    result.psd = estimate_psd(flat, Window::hann, heightmap::Form::none);
    const Psd2d& psd = result.psd;
    result.radial = radial_average(psd);
    result.kc = fit_kc(result.radial, nyquist_zeta(map), options);
    result.spectrum = heightmap::is_periodic(map) ? estimate_psd(flat, Window::rectangular, heightmap::Form::none) : psd;
    result.elliptical = fit_elliptical_kc(result.spectrum, result.kc);
    result.acv = acv_measures(flat);
    result.rms_height_um = heightmap::height_moments(flat).rms;
    result.rms_slope = rms_slope(flat, heightmap::Form::none);
    result.rms_slope_from_psd = rms_slope_from_psd(psd);
    // The fitted KC summed over the periodogram's own lattice against the periodogram there: the variance the fit
    // says the map should hold against what it holds, and the latter's relative standard error from its rings.
    const KCorrelation model(result.kc.sigma_h_um, result.kc.corr_length_um, result.kc.gamma);
    double fitted = 0.0;
    for (std::size_t ky = 0; ky < psd.ny; ++ky)
        for (std::size_t kx = 0; kx < psd.half_nx(); ++kx)
            fitted += psd.multiplicity(kx) * model.psd(std::hypot(psd.zeta_x(kx), psd.zeta_y(ky)));
    result.fit_lattice_rms_um = std::sqrt(fitted * psd.dzeta_x * psd.dzeta_y);
    result.map_lattice_rms_um = std::sqrt(std::max(0.0, psd.integral()));
    double mass = 0.0, variance = 0.0;
    for (std::size_t i = 0; i < result.radial.psd.size(); ++i) {
        const double m = std::max(result.radial.psd[i], 0.0) * result.radial.count[i];
        mass += m;
        variance += m * m / effective_samples(result.radial.window, result.radial.count[i], result.radial.valid_weight);
    }
    result.lattice_rms_error = mass > 0.0 ? 0.5 * std::sqrt(variance) / mass : 0.0;
    return result;
}

std::string lattice_rms_check(const SurfaceFit& f) {
    if (!(f.map_lattice_rms_um > 0.0)) return "";
    const double ratio = f.fit_lattice_rms_um / f.map_lattice_rms_um;
    const double allowed = std::max(kLatticeRmsTolerance, 3.0 * f.lattice_rms_error);
    if (std::abs(std::log(ratio)) <= std::log1p(allowed)) return "";
    return fmt::format(
        "the fitted KC (sigma_h {:.4g} um) holds an rms of {:.4g} um on the map's own frequencies, {:.3g} times the "
        "map's {:.4g} um (the map's standard error {:.2g} %): its band {:.4g} .. {:.4g} rad/um misses where the map's "
        "roughness lies (waviness below the band, a tail or noise above it); the KC parameters do not describe this "
        "map: use --psd measured, or prepare the map (--form, --lambda-c)",
        f.kc.sigma_h_um, f.fit_lattice_rms_um, ratio, f.map_lattice_rms_um, 100.0 * f.lattice_rms_error, f.kc.zeta_min,
        f.kc.zeta_max);
}

}  // namespace surfscatter::surface
