#include "surfscatter/bsdf/profile_lobes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <complex>
#include <functional>
#include <optional>
#include <string>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/bsdf/two_scale.hpp"
#include "surfscatter/surface/psd_split.hpp"
#include "surfscatter/surface/relevant_roughness.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace surfscatter::bsdf {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kIntegralTolerance = 1e-10;
constexpr double kGrading = 2.0;  // ratio of the panels toward x = 0
constexpr double kMaxPanels = 1e6;  // 16e6 nodes, 256 MB: a correlation length ~1e5 wavelengths
constexpr double kMinWavelengthNm = 0.1, kMaxWavelengthNm = 1e8;  // as the 2-D models (GhsBsdf)
// A PSD with a jump: |rho|'s envelope where the quadrature of the orders >= 2 (~ rho^2) starts its taper.
constexpr double kJumpTail = 1e-3;
// Such a lobe is accurate to ~2e-4 (its taper; TwoScaleMicroLobeMatchesThePoissonSeriesOfItsPsd): its normalisation
// is integrated to 1e-7, not kIntegralTolerance, which the taper's ripples kept the bisection from reaching (50 CPU s
// for one lobe of the supplemental's rough surface at 60 deg, bench_bsdf BM_two_scale_profile_lobe).
constexpr double kJumpIntegralTolerance = 1e-7;

// int_lo^hi f for an f peaked at `peak` with width ~`width`: adaptive Gauss-Kronrod on pieces peak +- width 10^j, so
// that the bisection starts at the peak's scale however narrow it is.
double integrate_peaked(const std::function<double(double)>& f, double lo, double hi, double peak, double width,
                        double rel_tol = kIntegralTolerance) {
    peak = std::clamp(peak, lo, hi);
    // Far pieces hold values at the round-off of the peak's: an absolute floor keeps the bisection off that noise.
    const double floor = 1e-13 * std::abs(f(peak)) * width;
    double total = 0;
    for (const double side : {-1.0, 1.0}) {
        const double end = side > 0 ? hi : lo;
        double from = peak;
        for (double w = width; side * (end - from) > 0; w *= 10) {
            const double to = side > 0 ? std::min(end, peak + w) : std::max(end, peak - w);
            total += math::integrate_adaptive(f, std::min(from, to), std::max(from, to), rel_tol, floor);
            from = to;
        }
    }
    return total;
}

double polarised_reflectance(const material::Conductor& conductor, double cos_theta, double lambda_nm,
                             ProfilePolarisation polarisation) {
    if (conductor.is_perfect()) return 1.0;
    const auto r = conductor.reflectance_sp(std::min(1.0, cos_theta), lambda_nm);
    return polarisation == ProfilePolarisation::s ? r.rs : r.rp;
}

// |Q_ss|^2 or |Q_pp|^2 of Rayleigh-Rice in the plane of incidence (rayleigh_rice.hpp's Q with the azimuth 0 or pi;
// sin theta_o signed, positive on the specular side). Equal to |r|^2 at the specular direction.
double rayleigh_rice_in_plane(const material::Conductor& conductor, double lambda_nm, ProfilePolarisation polarisation,
                              double theta_i, double theta_o) {
    const double si = std::sin(theta_i), ci = std::cos(theta_i), so = std::sin(theta_o), co = std::cos(theta_o);
    if (conductor.is_perfect()) {  // eps -> infinity
        if (polarisation == ProfilePolarisation::s) return 1.0;
        const double q = (1.0 - si * so) / (ci * co);
        return q * q;
    }
    const std::complex<double> n = conductor.ior(lambda_nm), eps = n * n;
    const std::complex<double> ri = std::sqrt(eps - si * si), ro = std::sqrt(eps - so * so);
    if (polarisation == ProfilePolarisation::s) return std::norm((eps - 1.0) / ((ci + ri) * (co + ro)));
    return std::norm((eps - 1.0) * (ri * ro - eps * si * so) / ((eps * ci + ri) * (eps * co + ro)));
}

double fresnel_factor(const material::Conductor& conductor, double lambda_nm, ProfilePolarisation polarisation,
                      FresnelMode mode, double theta_i, double theta_o) {
    switch (mode) {
        case FresnelMode::incident: return polarised_reflectance(conductor, std::cos(theta_i), lambda_nm, polarisation);
        case FresnelMode::half:
            return polarised_reflectance(conductor, std::cos(0.5 * std::abs(theta_i + theta_o)), lambda_nm,
                                         polarisation);
        case FresnelMode::rr: return rayleigh_rice_in_plane(conductor, lambda_nm, polarisation, theta_i, theta_o);
    }
    return 1.0;
}

}  // namespace

ProfileModel parse_profile_model(std::string_view text, const char* what) {
    if (text == "ghs") return ProfileModel::ghs;
    if (text == "ghs_ssa") return ProfileModel::ghs_ssa;
    if (text == "kirchhoff") return ProfileModel::kirchhoff;
    fail("{} must be one of ghs | ghs_ssa | kirchhoff, got '{}'", what, text);
}

std::string to_string(ProfileModel model) {
    switch (model) {
        case ProfileModel::ghs: return "ghs";
        case ProfileModel::ghs_ssa: return "ghs_ssa";
        case ProfileModel::kirchhoff: return "kirchhoff";
    }
    return "?";
}

ProfilePolarisation parse_profile_polarisation(std::string_view text, const char* what) {
    if (text == "s") return ProfilePolarisation::s;
    if (text == "p") return ProfilePolarisation::p;
    fail("{} must be s or p, got '{}'", what, text);
}

std::string inapplicable_profile_option(const std::vector<ProfileModel>& models, std::string_view option) {
    const auto chosen = [&](ProfileModel m) { return std::find(models.begin(), models.end(), m) != models.end(); };
    if (option == "fresnel" && !chosen(ProfileModel::ghs) && !chosen(ProfileModel::ghs_ssa))
        return "not used by kirchhoff (the tangent plane's |r(theta_d)|^2)";
    if (option == "renormalization" && !chosen(ProfileModel::ghs)) return "used by ghs only";
    if (option == "ssa_form" && !chosen(ProfileModel::ghs_ssa)) return "used by ghs_ssa only";
    return {};
}

ProfileAcvTransform::ProfileAcvTransform(const surface::RadialStatistics& statistics, double zeta_max) {
    require_positive(zeta_max, "largest profile frequency");
    const double length = statistics.correlation_length();
    const double jump = statistics.psd_jump_radius();
    // The ACV's reach: beyond rho < 1e-17 the integrand (at most g e^{-g} rho <= rho / e) no longer counts. A PSD with
    // a jump at zeta_j (a sharp cut's high-pass part) has an ACV ringing with the period 2 pi / zeta_j and decaying
    // only as x^-3/2: its first order is taken from the PSD (lobe, order) and the rest, ~rho^2, out to where the
    // ringing's envelope (|rho| over one period) is below kJumpTail, then tapered to 0 over as long again.
    const auto reached = [&](double x) {
        if (jump <= 0) return statistics.acv_normalized(x) < 1e-17;
        for (int j = 0; j < 16; ++j)
            if (std::abs(statistics.acv_normalized(x + j * (2 * kPi / jump) / 16)) > kJumpTail) return false;
        return true;
    };
    double x_max = length;
    while (!reached(x_max)) {
        x_max *= 2;
        if (x_max > 1e6 * length)
            fail("the profile ACV of {} does not decay below {:.0e} within 1e6 correlation lengths",
                 statistics.cache_key(), jump > 0 ? kJumpTail : 1e-17);
    }
    const double taper_from = jump > 0 ? x_max : std::numeric_limits<double>::infinity();
    if (jump > 0) {
        x_max *= 2;
        psd_ = &statistics;
    }
    const double panel = std::min(0.5 * length, 2.0 * kPi / zeta_max);  // one period of the fastest cosine at most
    static const math::GaussLegendreRule rule(16);
    const auto add_panel = [&](double a, double b) {
        for (std::size_t j = 0; j < rule.nodes.size(); ++j) {
            const double x = 0.5 * (a + b) + 0.5 * (b - a) * rule.nodes[j];
            // cos^2 taper over [taper_from, 2 taper_from]: what it leaves out is the ringing's, at frequencies within
            // a few zeta_j of 0, so that it moves the lobe near specular only (a hard end would ripple at every zeta)
            const double taper =
                x > taper_from ? 0.5 * (1 + std::cos(kPi * (x - taper_from) / taper_from)) : 1.0;
            x_.push_back(x);
            weight_.push_back(0.5 * (b - a) * rule.weights[j] * taper);
            rho_.push_back(statistics.acv_normalized(x));
        }
    };
    // Graded toward x = 0, where 1 - rho has its cusp (KC, gamma < 3) and e^{-g (1 - rho)} its width for large g.
    for (double b = panel; b > 1e-24 * length; b /= kGrading) add_panel(b / kGrading, b);
    const double count = std::ceil((x_max - panel) / panel);
    if (count > kMaxPanels)
        fail("the profile lobe of {} at zeta up to {} rad/um needs {:.3g} quadrature panels, more than {:.0e}",
             statistics.cache_key(), zeta_max, count, kMaxPanels);
    const double width = (x_max - panel) / count;
    for (double i = 0; i < count; ++i) add_panel(panel + i * width, panel + (i + 1) * width);
}

template <typename F>
double ProfileAcvTransform::transform(F&& f, double zeta) const {
    double sum = 0;
    for (std::size_t j = 0; j < x_.size(); ++j) sum += weight_[j] * f(rho_[j]) * std::cos(zeta * x_[j]);
    return sum / kPi;  // (2 pi)^-1 int over the whole line of an even function
}

double ProfileAcvTransform::first_order(double zeta) const {
    const double sigma = psd_->sigma_h();
    return surface::profile_psd(*psd_, zeta) / (sigma * sigma);
}

double ProfileAcvTransform::lobe(double g, double zeta) const {
    const double e_g = std::exp(-g);
    if (psd_) {  // g e^{-g} P1-hat from the PSD, the orders >= 2 from e^{-g} (e^{g rho} - 1 - g rho)
        const double rest = transform(
            [&](double rho) {
                const double a = g * rho;
                if (a > 1) return std::exp(-g * (1 - rho)) - e_g * (1 + a);
                if (std::abs(a) >= 0.5) return e_g * (std::expm1(a) - a);
                // e^a - 1 - a by its series where it would cancel
                double term = a * a / 2, sum = 0;
                for (int n = 3; std::abs(term) > 1e-17 * std::abs(sum); ++n) sum += term, term *= a / n;
                return e_g * sum;
            },
            zeta);
        return g * e_g * first_order(zeta) + rest;
    }
    // e^{-g} (e^{g rho} - 1) without overflow for large g nor cancellation for small g rho.
    return transform(
        [&](double rho) { return g * rho > 1 ? std::exp(-g * (1 - rho)) - e_g : e_g * std::expm1(g * rho); }, zeta);
}

double ProfileAcvTransform::order(int m, double zeta) const {
    if (m < 1) fail("self-convolution order must be >= 1, got {}", m);
    if (psd_ && m == 1) return first_order(zeta);
    return transform([&](double rho) { return std::pow(rho, m); }, zeta);
}

double profile_relevant_roughness(const surface::RadialStatistics& statistics, double theta_i_rad, double lambda_nm) {
    const double k = surface::wavenumber_per_um(lambda_nm), s = std::sin(theta_i_rad);
    const auto psd = [&](double zeta) { return surface::profile_psd(statistics, zeta); };
    return std::sqrt(integrate_peaked(psd, -k * (1 + s), k * (1 - s), 0.0, 1.0 / statistics.correlation_length()));
}

std::vector<double> uniform_theta_grid(int steps) {
    if (steps < 1) fail("theta grid needs at least 1 step, got {}", steps);
    std::vector<double> grid;
    for (int j = 0; j <= steps; ++j) grid.push_back((-90.0 + 180.0 * j / steps) * (kPi / 180));
    return grid;
}

void require_profile_wavelength(double lambda_nm, const std::string& name) {
    if (!(lambda_nm >= kMinWavelengthNm && lambda_nm <= kMaxWavelengthNm))
        fail("{} must be between {} and {} nm, got {}", name, kMinWavelengthNm, kMaxWavelengthNm, lambda_nm);
}

namespace {

void check_lobe_input(double lambda_nm, double theta_i_rad, const std::vector<double>& theta_o_rad) {
    require_profile_wavelength(lambda_nm, "wavelength");
    require_finite(theta_i_rad, "theta_i");
    if (theta_i_rad < 0 || theta_i_rad >= kPi / 2)
        fail("theta_i must be in [0, 90) degrees, got {}", theta_i_rad * 180 / kPi);
    require_list_size(theta_o_rad.size(), "theta_o");
    for (const double t : theta_o_rad)
        if (!(std::abs(t) <= kPi / 2)) fail("theta_o must be in [-90, 90] degrees, got {}", t * 180 / kPi);
}

}  // namespace

namespace {

// The 1-D GGX lobe of alpha^2 (header), without the input checks.
std::vector<double> ggx_lobe(double alpha2, const material::Conductor& conductor, double lambda_nm, double theta_i_rad,
                             ProfilePolarisation polarisation, const std::vector<double>& theta_o_rad) {
    const double alpha = std::sqrt(alpha2);
    const auto lambda = [&](double theta) {
        const double t = std::tan(theta);
        return 0.5 * (std::sqrt(1 + alpha2 * t * t) - 1);
    };
    const double ci = std::cos(theta_i_rad), lambda_i = lambda(theta_i_rad);
    std::vector<double> out;
    out.reserve(theta_o_rad.size());
    for (const double theta_o : theta_o_rad) {
        const double b = 0.5 * (theta_o - theta_i_rad), theta_d = 0.5 * (theta_i_rad + theta_o);
        const double p = std::tan(b), cb = std::cos(b);
        const double slope_density = 0.5 / (alpha * std::pow(1 + p * p / alpha2, 1.5));
        const double g2 = std::abs(theta_o) < kPi / 2 ? 1 / (1 + lambda_i + lambda(theta_o)) : 0.0;
        const double value = polarised_reflectance(conductor, std::cos(theta_d), lambda_nm, polarisation) * g2 *
                             slope_density * std::cos(theta_d) / (2 * cb * cb * cb * ci);
        if (!std::isfinite(value))
            fail("GGX profile lobe is not finite at theta_o {} deg (theta_i {} deg, {} nm)", theta_o * 180 / kPi,
                 theta_i_rad * 180 / kPi, lambda_nm);
        out.push_back(value);
    }
    return out;
}

}  // namespace

ProfileLobe ggx_profile_lobe(const surface::RadialStatistics& statistics, const material::Conductor& conductor,
                             double lambda_nm, double theta_i_rad, ProfilePolarisation polarisation,
                             const std::vector<double>& theta_o_rad) {
    check_lobe_input(lambda_nm, theta_i_rad, theta_o_rad);
    const double slope2 = statistics.mean_square_slope(0.0, std::numeric_limits<double>::infinity());
    if (!std::isfinite(slope2) || !(slope2 > 0))
        fail("ggx_stats: the rms slope of {} diverges (KC gamma <= 3): GGX from statistics has no alpha",
             statistics.cache_key());
    ProfileLobe out;
    out.intensity_per_rad = ggx_lobe(slope2, conductor, lambda_nm, theta_i_rad, polarisation, theta_o_rad);
    return out;
}

ProfileLobe profile_lobe(const surface::RadialStatistics& statistics, const material::Conductor& conductor,
                         double lambda_nm, double theta_i_rad, ProfilePolarisation polarisation,
                         const ProfileModelOptions& options, const std::vector<double>& theta_o_rad) {
    check_lobe_input(lambda_nm, theta_i_rad, theta_o_rad);
    const double k = surface::wavenumber_per_um(lambda_nm);
    const double si = std::sin(theta_i_rad), ci = std::cos(theta_i_rad);
    const double sigma_h = statistics.sigma_h(), variance = sigma_h * sigma_h;

    // sigma_rel in g and the albedo normalisation go together, as in the 2-D models.
    const bool renormalised = (options.model == ProfileModel::ghs && options.renormalization) ||
                              (options.model == ProfileModel::ghs_ssa && options.ssa_form == SsaForm::energy);
    ProfileLobe out;
    out.sigma_um = renormalised ? profile_relevant_roughness(statistics, theta_i_rad, lambda_nm) : sigma_h;
    const auto g_of = [&](double cos_o) {
        const double a = k * out.sigma_um * (ci + cos_o);
        return a * a;
    };
    const double g0 = g_of(ci);
    out.coherent = polarised_reflectance(conductor, ci, lambda_nm, polarisation) * std::exp(-g0);

    // The core lobe over u = sin theta_o (so that cos theta_o d theta_o = du) and its normalisation to 1 - e^{-g0}.
    std::optional<ProfileAcvTransform> acv;  // S_g for ghs and kirchhoff (SSA reads the profile PSD)
    if (options.model != ProfileModel::ghs_ssa) acv.emplace(statistics, k * (1 + si));
    const auto unit_psd = [&](double zeta) { return surface::profile_psd(statistics, zeta) / variance; };
    const auto density = [&](double cos_o, double zeta) {  // per unit u: the lobe's zeta-density times k
        switch (options.model) {
            case ProfileModel::ghs:
            case ProfileModel::kirchhoff: return k * acv->lobe(g_of(cos_o), zeta);
            case ProfileModel::ghs_ssa: {
                const double g = g_of(cos_o);
                return k * unit_psd(zeta) * (options.ssa_form == SsaForm::energy ? -std::expm1(-g) : g);
            }
        }
        return 0.0;
    };
    if (renormalised) {
        const auto integrand = [&](double u) { return density(std::sqrt(std::max(0.0, 1 - u * u)), k * (u - si)); };
        const double width = std::min(1.0, 1.0 / (k * statistics.correlation_length()));
        const double mass = integrate_peaked(integrand, -1.0, 1.0, si, width,
                                             statistics.psd_jump_radius() > 0 ? kJumpIntegralTolerance
                                                                              : kIntegralTolerance);
        if (!(mass > 0))
            fail("the {} lobe of {} has no mass over the visible directions at {} nm, theta_i {} deg",
                 to_string(options.model), statistics.cache_key(), lambda_nm, theta_i_rad * 180 / kPi);
        out.normalization = -std::expm1(-g0) / mass;
    }

    out.intensity_per_rad.reserve(theta_o_rad.size());
    for (const double theta_o : theta_o_rad) {
        const double co = std::max(0.0, std::cos(theta_o));
        const double zeta = k * (std::sin(theta_o) - si);
        double value;
        if (options.model == ProfileModel::kirchhoff) {
            const double obliquity = (1 + std::cos(theta_i_rad + theta_o)) / (ci + co);
            value = fresnel_factor(conductor, lambda_nm, polarisation, FresnelMode::half, theta_i_rad, theta_o) *
                    density(co, zeta) * obliquity * obliquity / ci;
        } else {
            value = co > 0 ? fresnel_factor(conductor, lambda_nm, polarisation, options.fresnel, theta_i_rad, theta_o) *
                                 out.normalization * co * density(co, zeta)
                           : 0.0;
        }
        if (!std::isfinite(value))
            fail("{} lobe is not finite at theta_o {} deg (theta_i {} deg, {} nm)", to_string(options.model),
                 theta_o * 180 / kPi, theta_i_rad * 180 / kPi, lambda_nm);
        out.intensity_per_rad.push_back(std::max(0.0, value));  // the quadrature's round-off below zero
    }
    return out;
}

ProfileLobe two_scale_profile_lobe(const surface::RadialStatistics& statistics, const material::Conductor& conductor,
                                   double lambda_nm, double theta_i_rad, ProfilePolarisation polarisation,
                                   const std::vector<double>& theta_o_rad, double cutoff_wavelengths) {
    check_lobe_input(lambda_nm, theta_i_rad, theta_o_rad);
    require_finite(cutoff_wavelengths, "two_scale cutoff_wavelengths");
    require_positive(cutoff_wavelengths, "two_scale cutoff_wavelengths");
    const double zeta_c = surface::cutoff_frequency(kTwoScaleReferenceWavelength, cutoff_wavelengths);
    // The split keeps its base only for this call: a non-owning pointer.
    const std::shared_ptr<const surface::RadialStatistics> base(std::shared_ptr<const void>(), &statistics);
    const surface::PsdSplit split = surface::split_psd(base, zeta_c, surface::LowPassFilter::sharp);
    if (!(split.slope2_macro > 0) || !std::isfinite(split.slope2_macro))
        fail("two_scale: the low-pass part of {} below zeta_c {:.4g} rad/um has rms slope {}: no macro NDF",
             statistics.cache_key(), zeta_c, std::sqrt(split.slope2_macro));
    ProfileLobe out;
    double macro_weight = 1, micro_energy = 0;
    if (split.micro) {
        out = profile_lobe(*split.micro, conductor, lambda_nm, theta_i_rad, polarisation, ProfileModelOptions{},
                           theta_o_rad);
        const double a = 2 * surface::wavenumber_per_um(lambda_nm) * out.sigma_um * std::cos(theta_i_rad);
        macro_weight = std::exp(-a * a);
        // R (1 - e^{-g0}): the lobe is K renormalised to it
        micro_energy = -polarised_reflectance(conductor, std::cos(theta_i_rad), lambda_nm, polarisation) *
                       std::expm1(-a * a);
        out.coherent = 0;
    } else {
        out.intensity_per_rad.assign(theta_o_rad.size(), 0.0);
    }
    const std::vector<double> macro =
        ggx_lobe(split.slope2_macro, conductor, lambda_nm, theta_i_rad, polarisation, theta_o_rad);
    for (std::size_t j = 0; j < macro.size(); ++j) out.intensity_per_rad[j] += macro_weight * macro[j];
    const auto macro_at = [&](double theta_o) {
        return ggx_lobe(split.slope2_macro, conductor, lambda_nm, theta_i_rad, polarisation, {theta_o}).front();
    };
    // The lobe's width in theta_o is about 2 alpha (theta_o = theta_i + 2 b).
    out.energy = micro_energy + macro_weight * integrate_peaked(macro_at, -kPi / 2, kPi / 2, theta_i_rad,
                                                                2 * std::sqrt(split.slope2_macro));
    return out;
}

}  // namespace surfscatter::bsdf
