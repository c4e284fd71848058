#pragma once
// The isotropic scattered part of a wave-optical lobe over the zeta plane, as a function of the roughness
// exponent g (THEORY 1.2): the GHS core S_g(zeta) = e^-g sum_{m>=1} g^m/m! P-hat^{*m}(zeta) (exactly from the
// surface engine's S_g table, or by the paper's KC-refit series), or a first-order lobe (SSA). Densities are per
// (rad/um)^2; the BRDF is k^2 times a density (THEORY 0). Each core also draws |zeta| <= zeta_max from the lobe at a
// fixed g* and reports the exact 2-D density of what it draws, for the wedge sampler (wedge_sampling.hpp).
#include <memory>
#include <string>
#include <vector>

#include "surfscatter/math/fast_math.hpp"

namespace surfscatter::bsdf {

class ScatterCore {
public:
    virtual ~ScatterCore() = default;
    // Lobe density at exponent g and radius zeta (rad/um).
    virtual double density(double g, double zeta) const = 0;
    // density(e^{log_g}, e^{log_zeta}): the BSDF has g and zeta as logarithms, which the exact core's log-spaced
    // table uses directly.
    virtual double density_at_logs(double log_g, double log_zeta) const {
        return density(math::fast_exp(log_g), math::fast_exp(log_zeta));
    }
    // Draws a radius in [0, zeta_max] for the lobe at g_star; u_order (may be unused) and u in [0, 1).
    virtual double sample_radius(double g_star, double zeta_max, double u_order, double u) const = 0;
    // 2-D density (per (rad/um)^2, unit mass over |zeta| <= zeta_max) of sample_radius followed by a uniform
    // azimuth over the full circle.
    virtual double sample_density(double g_star, double zeta_max, double zeta) const = 0;
    // Everything density() depends on, as text: a key for tables derived from the core (GhsBsdf's, cached on disk).
    virtual std::string cache_key() const = 0;
};

}  // namespace surfscatter::bsdf

#include "surfscatter/bsdf/lazy_slots.hpp"
#include "surfscatter/bsdf/model_options.hpp"
#include "surfscatter/bsdf/poisson.hpp"
#include "surfscatter/bsdf/radial_proposal.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/refit.hpp"
#include "surfscatter/surface/scatter_lobe_table.hpp"

namespace surfscatter::bsdf {

// The full lobe from the surface engine's S_g table: no series, cost independent of g. Sampling draws from a
// RadialProposal of S_{g_q}, g_q = g* rounded to 16 nodes per decade (proposals built once, read lock-free),
// truncated to |zeta| <= zeta_max; the pdf is that proposal's exact density. g above ScatterLobeTable::kMaxG (1e6) is
// evaluated at kMaxG.
class ExactScatterCore final : public ScatterCore {
public:
    explicit ExactScatterCore(std::shared_ptr<const surface::RadialStatistics> stats);
    double density(double g, double zeta) const override;
    double density_at_logs(double log_g, double log_zeta) const override {
        return table_->eval_at_logs(log_g, log_zeta);
    }
    // The lobe table itself: for a PSD without a jump (whose table is log-valued) the GHS BSDF reads ln S_g from it
    // inline, adds ln N and takes one exponential.
    const surface::ScatterLobeTable& table() const { return *table_; }
    double sample_radius(double g_star, double zeta_max, double u_order, double u) const override;
    double sample_density(double g_star, double zeta_max, double zeta) const override;
    std::string cache_key() const override { return "exact(" + table_->key() + ")"; }

private:
    const RadialProposal& proposal(double g_star) const;
    std::shared_ptr<const surface::ScatterLobeTable> table_;
    LazySlots<RadialProposal> proposals_;  // per g* node
};

// The paper's method (supplemental eqs 1-2): Poisson series over the orders kept by the truncation rule, each
// P-hat^{*m} replaced by a KC of the same gamma and length L m^-x (x from refit_self_convolutions). Sampling:
// order m from the kept Poisson(g*) window (by u_order), then the truncated KC inversion of eqs 3-4.
class RefitScatterCore final : public ScatterCore {
public:
    RefitScatterCore(const surface::KCorrelation& kc, double exponent_x, Truncation truncation, double epsilon);
    double density(double g, double zeta) const override;
    double sample_radius(double g_star, double zeta_max, double u_order, double u) const override;
    double sample_density(double g_star, double zeta_max, double zeta) const override;
    std::string cache_key() const override;
    double order_length(int m) const;  // L m^-x, um

private:
    PoissonWindow window(double g) const;
    surface::KCorrelation order_statistics(int m) const;  // unit-sigma KC of order m (precomputed up to kOrders)
    static constexpr int kOrders = 2048;
    double length_, gamma_, exponent_x_;
    std::vector<surface::KCorrelation> orders_;  // index m - 1
    Truncation truncation_;
    double epsilon_;
};

// First-order (smooth-surface) lobe: (1 - e^-g) P-hat (energy form) or g P-hat (strict form), THEORY 1.4.
class FirstOrderCore final : public ScatterCore {
public:
    FirstOrderCore(std::shared_ptr<const surface::RadialStatistics> stats, SsaForm form);
    double density(double g, double zeta) const override;
    double sample_radius(double g_star, double zeta_max, double u_order, double u) const override;
    double sample_density(double g_star, double zeta_max, double zeta) const override;
    std::string cache_key() const override;

private:
    std::shared_ptr<const surface::RadialStatistics> stats_;
    SsaForm form_;
};

// Radius with radial_cdf(zeta) = u for any statistics (closed forms for KC and Gaussian, bisection otherwise).
double inverse_radial_cdf(const surface::RadialStatistics& stats, double u);

}  // namespace surfscatter::bsdf
