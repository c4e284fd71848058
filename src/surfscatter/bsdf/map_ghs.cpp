#include "surfscatter/bsdf/map_ghs.hpp"

#include <algorithm>
#include <cmath>
#include <atomic>
#include <exception>
#include <limits>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "surfscatter/bsdf/wedge_sampling.hpp"  // wavenumber
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/math/fast_math.hpp"
#include "surfscatter/math/lagrange.hpp"

namespace surfscatter::bsdf {

namespace {

const NodeAxis kIncidenceAxis = ghs_incidence_axis();
const NodeAxis kWavelengthAxis = ghs_wavelength_axis();
constexpr double kAzimuthStep = kPi / MapGhsBsdf::kAzimuthNodes;
constexpr int kRefinedAzimuths = MapGhsBsdf::kAzimuthNodes * MapGhsBsdf::kRefinement;
constexpr double kRefinedStep = kPi / kRefinedAzimuths;

// The incidence at cos theta_i = c and azimuth phi.
Vec3 incidence(double c, double phi) {
    const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
    return {s * std::cos(phi), s * std::sin(phi), c};
}

}  // namespace

std::shared_ptr<const surface::SpectrumLobes2d> map_lobes(const surface::Psd2d& spectrum) {
    // sigma_rel <= sigma_h; the 2 % margin covers the cubics' overshoot of the tabulated sigma.
    const double sigma_h = std::sqrt(spectrum.integral());
    const double a = 2.0 * 1.02 * wavenumber(MapGhsBsdf::kMinWavelength) * sigma_h;
    return std::make_shared<const surface::SpectrumLobes2d>(spectrum, std::max(a * a, 2.0 * surface::SpectrumLobes2d::kMinG));
}

MapGhsBsdf::MapGhsBsdf(std::shared_ptr<const surface::SpectrumLobes2d> lobes, std::optional<SsaForm> ssa,
                       material::Conductor material, GhsSettings settings)
    : lobes_(std::move(lobes)), ssa_(ssa), material_(std::move(material)), settings_(std::move(settings)),
      tables_(std::size_t(kWavelengthAxis.size())) {
    if (!lobes_) fail("{} on a measured 2-D spectrum needs its lobes", settings_.name);
}

double MapGhsBsdf::density(double g, Vec2 zeta) const { return density(g, math::fast_log(g), zeta); }

double MapGhsBsdf::density(double g, double log_g, Vec2 zeta) const {
    if (!ssa_) return lobes_->eval(g, log_g, zeta);
    const double weight = *ssa_ == SsaForm::strict ? g : math::one_minus_exp(g);
    return weight * lobes_->first_order(zeta);
}

[[gnu::always_inline]] inline const MapGhsBsdf::RefinedTables& MapGhsBsdf::table(int slot, bool show_progress) const {
    return tables_.get(std::size_t(slot),
                       [&] { return refine(cached_tables(kWavelengthAxis.node(slot), show_progress)); });
}

// Inlined into its callers, with eval's: as GhsBsdf's (the calls and the Incidence passed through memory cost a
// fifth of an eval).
[[gnu::always_inline]] inline MapGhsBsdf::Incidence MapGhsBsdf::interpolate(const Vec3& wi, double lambda_nm) const {
    if (!(lambda_nm >= kMinWavelength && lambda_nm <= kGhsMaxWavelength))
        fail("wavelength {} nm outside [{}, {}] nm, the range of {} on a measured 2-D spectrum", lambda_nm,
             kMinWavelength, kGhsMaxWavelength, settings_.name);
    const NodeAxis::Position l = kWavelengthAxis.position(lambda_nm);
    const double cosine = std::clamp(wi.z, kIncidenceAxis.node(0), 1.0);
    const int c = kIncidenceAxis.position(cosine).interval;
    const math::Pair d = math::Pair{1.0, 1.0} * (cosine - kIncidenceAxis.node(c));
    // Azimuth: linear between the refined nodes around x = phi_i / step (pi-periodic).
    double phi = math::fast_atan2(wi.y, wi.x);
    if (phi < 0) phi += kPi;
    double x = phi * (1.0 / kRefinedStep);
    if (!(x >= 0.0)) x = 0.0;  // NaN components: a node, and the eval's finite check returns 0
    const int i = std::min(int(x), kRefinedAzimuths - 1), next = i + 1 < kRefinedAzimuths ? i + 1 : 0;
    const double t = x - double(i);
    auto at = [&](const RefinedTables& tables) {
        const math::Pair a = estrin(tables[std::size_t(i)][std::size_t(c)], d);
        return a + t * (estrin(tables[std::size_t(next)][std::size_t(c)], d) - a);
    };
    const math::Pair at_a = at(table(l.interval)), v = at_a + l.t * (at(table(l.interval + 1)) - at_a);
    return {wavenumber(lambda_nm), v[0], v[1]};
}

[[gnu::always_inline]] inline double MapGhsBsdf::eval(const Vec3& wi, const Vec3& wo, double lambda_nm,
                                                      const Incidence& in) const {
    // ln g = 2 ln(k (cos i + cos o)) + 2 ln sigma: the first term does not wait for the lookup.
    const double k = in.k, log_g = 2.0 * (math::fast_log(k * (wi.z + wo.z)) + in.log_sigma);
    const double lobe = density(math::fast_exp(log_g), log_g, Vec2(k * (wi.x + wo.x), k * (wi.y + wo.y)));
    const double f = lobe_fresnel(material_, settings_.fresnel, wi, wo, lambda_nm) * math::fast_exp(in.log_norm) *
                     norm_power(wi.z) * k * k * lobe;
    return std::isfinite(f) ? f : 0.0;
}

MapGhsBsdf::Incidence MapGhsBsdf::lookup(const Vec3& wi, double lambda_nm) const { return interpolate(wi, lambda_nm); }

double MapGhsBsdf::eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0;
    return eval(wi, wo, lambda_nm, interpolate(wi, lambda_nm));
}

double MapGhsBsdf::pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0;
    return pdf(wi, wo, lookup(wi, lambda_nm));
}

double MapGhsBsdf::pdf(const Vec3& wi, const Vec3& wo, const Incidence& in) const {
    const double k = in.k, g0 = specular_exponent(in, wi.z);
    const double p = -std::expm1(-g0) * k * k * wo.z *
                     lobes_->sample_density(g0, ssa_.has_value(), Vec2(k * (wi.x + wo.x), k * (wi.y + wo.y)));
    return std::isfinite(p) ? p : 0.0;
}

std::optional<BsdfSample> MapGhsBsdf::sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const {
    if (wi.z <= 0) return std::nullopt;
    const Incidence in = lookup(wi, lambda_nm);
    const double k = in.k, g0 = specular_exponent(in, wi.z), p_delta = std::exp(-g0);
    if (u_lobe < p_delta) return coherent_delta_sample(material_, wi, lambda_nm, p_delta);
    const double u_row = std::min((u_lobe - p_delta) / (1.0 - p_delta), std::nextafter(1.0, 0.0));
    const Vec2 zeta = lobes_->sample(g0, ssa_.has_value(), u_row, u);
    const double ox = zeta.x / k - wi.x, oy = zeta.y / k - wi.y, z2 = 1.0 - ox * ox - oy * oy;
    if (!(z2 > 0)) return std::nullopt;  // outside the visible disc: a failed sample (the pdf's missing mass)
    BsdfSample out;
    out.wo = Vec3(ox, oy, std::sqrt(z2));
    out.pdf = pdf(wi, out.wo, in);
    if (!(out.pdf > 0) || !std::isfinite(out.pdf)) return std::nullopt;
    out.weight = eval(wi, out.wo, lambda_nm, in) * out.wo.z / out.pdf;
    if (!std::isfinite(out.weight)) return std::nullopt;
    return out;
}

double MapGhsBsdf::delta_probability(const Vec3& wi, double lambda_nm) const {
    if (wi.z <= 0) return 0.0;
    const Incidence in = lookup(wi, lambda_nm);
    return std::exp(-specular_exponent(in, wi.z));
}

double MapGhsBsdf::delta_reflectance(const Vec3& wi, double lambda_nm) const {
    if (wi.z <= 0) return 0.0;
    return material_.reflectance(std::min(1.0, wi.z), lambda_nm) * delta_probability(wi, lambda_nm);
}

void MapGhsBsdf::tabulate(double lambda_lo_nm, double lambda_hi_nm, unsigned threads) const {
    if (!(lambda_lo_nm >= kMinWavelength && lambda_hi_nm <= kGhsMaxWavelength && lambda_lo_nm <= lambda_hi_nm))
        fail("wavelengths {} .. {} nm outside [{}, {}] nm, the range of {} on a measured 2-D spectrum", lambda_lo_nm,
             lambda_hi_nm, kMinWavelength, kGhsMaxWavelength, settings_.name);
    const int first = kWavelengthAxis.position(lambda_lo_nm).interval;
    const int last = kWavelengthAxis.position(lambda_hi_nm).interval + 1;
    // Every node's disc integrals hold about the same cells (k / kDiscCells per cell, or coarser).
    const double cells = kPi * (kDiscCells + 1.0) * (kDiscCells + 1.0);
    Progress progress(fmt::format("{} tables of the measured 2-D spectrum, {} wavelengths {:.4g} .. {:.4g} nm",
                                  settings_.name, last - first + 1, lambda_lo_nm, lambda_hi_nm),
                      std::uint64_t(last - first + 1), disc_work(cells) * (last - first + 1) > 5e7);
    std::atomic<int> next{first};
    std::exception_ptr error;
    std::mutex error_mutex;
    const auto work = [&] {
        try {
            for (int slot = next++; slot <= last; slot = next++) {
                table(slot, false);
                progress.advance();
            }
        } catch (...) {
            std::lock_guard lock(error_mutex);
            if (!error) error = std::current_exception();
            next = last + 1;
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < std::max(1u, threads); ++t) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    if (error) std::rethrow_exception(error);
    progress.finish();
}

MapGhsBsdf::AzimuthTables MapGhsBsdf::cached_tables(double lambda_nm, bool show_progress) const {
    constexpr std::uint32_t kVersion = 1;  // of build_tables' construction and the layout
    const std::string key = fmt::format(
        "ghs-map2d-incidence:{}:lobe={}:normalization={}:relevant={}:lambda={:.17g}:nodes={}x{}",
        lobes_->key(), ssa_ ? "first-order-" + to_string(*ssa_) : std::string("full"), int(settings_.normalization),
        settings_.relevant_roughness, lambda_nm, kGhsThetaNodes, kAzimuthNodes);
    return cached_incidence_table<AzimuthTables>("ghs-map2d-incidence", kVersion, key,
                                                 [&] { return build_tables(lambda_nm, show_progress); });
}

// The periodic 4-point Lagrange cubic through the tabulated azimuth nodes, at kRefinement points per node interval:
// the cubics in cos theta_i are linear in their coefficients, so the coefficients combine with the Lagrange weights.
MapGhsBsdf::RefinedTables MapGhsBsdf::refine(const AzimuthTables& tables) {
    RefinedTables refined;  // returned in place (NRVO): LazySlots constructs it on the heap
    for (int base = 0; base < kAzimuthNodes; ++base)
        for (int r = 0; r < kRefinement; ++r) {
            const std::array<double, 4> w = math::lagrange4_weights(1.0 + double(r) / kRefinement);
            IncidenceTable& out = refined[std::size_t(base * kRefinement + r)];
            for (std::size_t c = 0; c < out.size(); ++c)
                for (int p = 0; p < 4; ++p)
                    for (int lane = 0; lane < 2; ++lane) {
                        double sum = 0;
                        for (int j = 0; j < 4; ++j) {
                            const int node = (base - 1 + j + kAzimuthNodes) % kAzimuthNodes;
                            sum += w[std::size_t(j)] * tables[std::size_t(node)][c].c[p][lane];
                        }
                        out[c].c[p][lane] = sum;
                    }
        }
    return refined;
}

MapGhsBsdf::AzimuthTables MapGhsBsdf::build_tables(double lambda_nm, bool show_progress) const {
    AzimuthTables tables;
    // Its own bins, passed to every integral: threads building other wavelengths' tables at once (a render) would
    // otherwise replace disc_bins' one kept set under each other, rebuilding it per integral (3/4 of a render's time).
    const auto bins = make_disc_bins(wavenumber(lambda_nm));
    const double disc_cells = kPi * std::pow(wavenumber(lambda_nm) / bins->h + 1.0, 2);
    Progress progress(fmt::format("{} tables of the measured 2-D spectrum at {:.4g} nm", settings_.name, lambda_nm),
                      kAzimuthNodes, show_progress && disc_work(disc_cells) > 5e7);
    for (int a = 0; a < kAzimuthNodes; ++a) {
        tables[std::size_t(a)] = tabulate_incidence(
            kIncidenceAxis,
            [&](double cos_theta_i) { return direct(incidence(cos_theta_i, a * kAzimuthStep), lambda_nm, *bins); },
            [this](double c) { return norm_power(c); });
        progress.advance();
    }
    progress.finish();
    return tables;
}

std::shared_ptr<const surface::SpectrumLobes2d::Bins> MapGhsBsdf::make_disc_bins(double k) const {
    // Cells of k / kDiscCells, or the finest row lattice that any g of this wavelength reads if that is coarser, over
    // every visible disc (|zeta| <= 2 k).
    const double b = k * lobes_->sigma_h(), g_hi = 4.0 * b * b;
    const double h = std::max(k / kDiscCells, lobes_->finest_spacing(0.0, g_hi));
    return std::make_shared<const surface::SpectrumLobes2d::Bins>(lobes_->bins(h, 2.0 * k + h, g_hi));
}

std::shared_ptr<const surface::SpectrumLobes2d::Bins> MapGhsBsdf::disc_bins(double k) const {
    std::lock_guard lock(bins_mutex_);
    if (!bins_ || bins_k_ != k) {
        bins_ = make_disc_bins(k);
        bins_k_ = k;
    }
    return bins_;
}

GhsBsdf::Direct MapGhsBsdf::direct(const Vec3& wi, double lambda_nm) const {
    return direct(wi, lambda_nm, *disc_bins(wavenumber(lambda_nm)));
}

GhsBsdf::Direct MapGhsBsdf::direct(const Vec3& wi, double lambda_nm, const surface::SpectrumLobes2d::Bins& bins) const {
    const double k = wavenumber(lambda_nm), ci = wi.z;
    const Vec2 centre(k * wi.x, k * wi.y);
    const bool needs_mass = settings_.relevant_roughness || settings_.normalization == LobeNormalization::disc_mass;
    const double disc_mass =
        needs_mass ? std::clamp(lobes_->disc_cells(bins, centre, k, [&](std::size_t cell, Vec2) {
                         return bins.mass[0][cell];
                     }), 0.0, 1.0)
                   : 1.0;
    const double sigma = settings_.relevant_roughness ? lobes_->sigma_h() * std::sqrt(disc_mass) : lobes_->sigma_h();
    switch (settings_.normalization) {
        case LobeNormalization::none: return {sigma, 1.0};
        case LobeNormalization::disc_mass: return {sigma, disc_mass > 0 ? 1.0 / disc_mass : 1.0};
        case LobeNormalization::albedo: {
            // int over the visible disc of S_{g(o)}(zeta) d^2 zeta, zeta = k (i_xy + o_xy): the product rule over the
            // cells of disc_bins, each cell's mass of every row times the weights of g at its centre.
            const double a = 2.0 * k * sigma * ci, b = k * sigma;
            const double mass = lobes_->disc_cells(bins, centre, k, [&](std::size_t cell, Vec2 zeta) {
                const double ox = zeta.x / k - wi.x, oy = zeta.y / k - wi.y;
                const double co = std::sqrt(std::max(0.0, 1.0 - ox * ox - oy * oy)), c = b * (ci + co), g = c * c;
                const double weight = ssa_ == SsaForm::strict ? g : math::one_minus_exp(g);  // as density()
                return weight * lobes_->binned_shape(bins, cell, g, ssa_.has_value());
            });
            return {sigma, mass > 0 ? -std::expm1(-a * a) / mass : 1.0};
        }
    }
    return {sigma, 1.0};
}

}  // namespace surfscatter::bsdf
