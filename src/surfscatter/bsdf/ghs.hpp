#pragma once
// The GHS family of BRDFs (THEORY 1): a coherent specular delta R(theta_i) e^{-g0} plus a scattered lobe
//   f_r(i, o) = F(i, o) * N(theta_i, lambda) * k^2 * core.density(g(theta_i, theta_o), k |i_xy + o_xy|),
//   g = (k sigma (cos theta_i + cos theta_o))^2,  g0 = g(theta_i, theta_i),
// where sigma is the relevant roughness sigma_rel(theta_i, lambda) or sigma_h, F the Fresnel factor
// (incident / half / rr), and N the lobe normalisation: K(theta_i, lambda) making the directional albedo exactly R
// (full GHS, THEORY 1.1 eq 20, and the SSA energy form), sigma_h^2 / sigma_rel^2 (the visible-disc mass) or 1.
// ln sigma and ln(N / cos^p theta_i) (p = 2 for the albedo normalisation K, which vanishes like cos^2 theta_i at
// grazing while K / cos^2 stays finite; p = 0 otherwise) are tabulated per wavelength node (2 % apart over
// [kMinWavelength, kMaxWavelength]; other wavelengths are an Error) over cos theta_i at 64 nodes from 1e-6 (theta_i
// 89.99994 deg) to 1, theta_j = 90 deg (1 - (1 - j/63)^3), built lazily (64 visible-disc integrals, ~30 ms; kept in
// the disk cache under a key naming the statistics, sigma_h, the core and the settings) and read without a lock. Between
// incidence nodes both are cubic in cos theta_i (the 4-point Lagrange cubic of each interval, stored as polynomial
// coefficients), between wavelength nodes linear in lambda; below cos theta_i = 1e-6 the end values hold (K itself
// still scales with cos^2). Nodes are found by NodeAxis (no log, no acos). eval hands ln g and ln zeta to the core (the
// exact core's table is log-spaced in both) and, for the exact core of a PSD without a jump, takes one exponential of
// ln N + ln S_g: two logarithms and one exponential per call, the logarithms taken before the lookup so that they
// overlap with it; other cores return the density, which exp(ln N) multiplies. Accuracy (Ghs.TabulatedSigmaAnd...,
// Ghs.EvalMatchesTheBrdfBuiltFromDirectValues): the lookup's sigma within 5e-4 and N within 1e-3 of their direct
// values (measured 3.0e-4, 5.4e-4); eval equals R N k^2 S_g at the looked-up sigma and N to 1e-13 relative, and its
// relative L1 distance over the lobe to the BRDF with sigma and N computed directly is below 2e-3 (measured 4e-4).
// Sampling: the delta with probability e^{-g0}; otherwise |zeta| from the core at g* = g0 and the azimuth over the
// visible wedge; the pdf is exact (wedge_pdf).
#include <array>
#include <cmath>
#include <memory>
#include <string>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/bsdf/incidence_tables.hpp"
#include "surfscatter/bsdf/lazy_slots.hpp"
#include "surfscatter/bsdf/model_options.hpp"
#include "surfscatter/bsdf/scatter_core.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::bsdf {

enum class LobeNormalization { albedo, disc_mass, none };

struct GhsSettings {
    std::string name = "ghs";
    FresnelMode fresnel = FresnelMode::incident;
    LobeNormalization normalization = LobeNormalization::albedo;
    bool relevant_roughness = true;  // sigma_rel(theta_i, lambda) in g, else sigma_h
};

class GhsBsdf final : public Bsdf {
public:
    static constexpr double kMinWavelength = kGhsMinWavelength;  // nm
    static constexpr double kMaxWavelength = kGhsMaxWavelength;  // nm
    static constexpr int kThetaNodes = kGhsThetaNodes;           // incidence nodes of the sigma / N tables

    GhsBsdf(std::shared_ptr<const surface::RadialStatistics> stats, std::shared_ptr<const ScatterCore> core,
            material::Conductor material, GhsSettings settings);

    double eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    std::optional<BsdfSample> sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const override;
    double pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    // The four wavelengths of a path: the logarithms of the direction-only factors of g and zeta, and the reverse
    // density's wedge geometry (an arccosine), computed once; the lookups and the lobe per wavelength.
    WavelengthValues eval_packet(const Vec3& wi, const Vec3& wo, const WavelengthValues& lambda_nm,
                                 WavelengthValues* pdf) const override;
    double delta_reflectance(const Vec3& wi, double lambda_nm) const override;
    double delta_probability(const Vec3& wi, double lambda_nm) const override;
    double jump_radius(double lambda_nm) const override;  // where the PSD jumps, in q
    std::string name() const override { return settings_.name; }

    // The roughness used in g (um) and the lobe normalisation N at (theta_i, lambda), as tabulated.
    double sigma(double cos_theta_i, double lambda_nm) const {
        return std::exp(lookup(cos_theta_i, lambda_nm).log_sigma);
    }
    double normalization(double cos_theta_i, double lambda_nm) const {
        return std::exp(lookup(cos_theta_i, lambda_nm).log_norm) * norm_power(cos_theta_i);
    }
    // Both computed directly at (theta_i, lambda), as at the table's nodes (an integral over the visible disc, ~1 ms):
    // the reference for the tabulation's accuracy.
    struct Direct {
        double sigma, norm;
    };
    Direct direct(double theta_i, double lambda_nm) const;
    // eval with sigma and N given (direct() at wi's incidence) instead of read from the tables, which are then never
    // built: for a few incidences (a fit's data, inverse/fit_brdf.cpp) far cheaper than the tables' 64 incidences per
    // wavelength node, and free of their interpolation error (eval is within it of this).
    double eval(const Vec3& wi, const Vec3& wo, double lambda_nm, const Direct& at) const;
    // The core lobe without Fresnel and normalisation: k^2 density(g, zeta) (symmetric in wi <-> wo when sigma is).
    double core_lobe(const Vec3& wi, const Vec3& wo, double lambda_nm, double sigma_um) const;

private:
    using Interval = CubicPairInterval;  // ln sigma and ln(N / cos^p)
    using Table = IncidenceTable;
    using Incidence = IncidenceLookup;
    Incidence lookup(double cos_theta_i, double lambda_nm) const;
    Incidence lookup(double cos_theta_i, double lambda_nm, double k) const;  // k = wavenumber(lambda_nm), given
    double norm_power(double cos_theta_i) const {  // cos^p theta_i
        return settings_.normalization == LobeNormalization::albedo ? cos_theta_i * cos_theta_i : 1.0;
    }
    struct LobeLogs {  // ln g - 2 ln sigma and ln zeta of a direction pair
        LobeLogs(const Vec3& wi, const Vec3& wo, double k);
        LobeLogs(double log_k, double log_cosine_sum, double log_radius2)  // ln k, ln(cos i + cos o), ln |i_xy + o_xy|^2
            : log_g_over_sigma2(2.0 * (log_k + log_cosine_sum)), log_zeta(log_k + 0.5 * log_radius2) {}
        double log_g_over_sigma2, log_zeta;
    };
    // The lobe with the incidence already looked up (in: at wi.z and lambda_nm).
    double eval(const Vec3& wi, const Vec3& wo, double lambda_nm, const Incidence& in, const LobeLogs& logs) const;
    struct Wedge {  // the pdf's geometry: sin theta_i, q = |i_xy + o_xy| and the wedge half-angle
        Wedge(const Vec3& wi, const Vec3& wo);
        double s, q, phi_max;
    };
    double pdf(const Vec3& wi, const Vec3& wo, const Incidence& in, const Wedge& wedge) const;  // in: at wi.z
    double density(const LobeLogs& logs, double log_sigma) const;
    Table cached_table(double lambda_nm) const;  // from the disk cache, else built and saved there
    Table build_table(double lambda_nm) const;
    double scatter_mass(double theta_i, double lambda_nm, double sigma_um) const;  // integral of density over disc
    double fresnel(const Vec3& wi, const Vec3& wo, double lambda_nm) const;

    std::shared_ptr<const surface::RadialStatistics> stats_;
    std::shared_ptr<const ScatterCore> core_;
    material::Conductor material_;
    GhsSettings settings_;
    const ExactScatterCore* exact_;       // core_ if it is the exact one (called directly), else null
    const surface::ScatterLobeTable* log_native_;  // exact_'s table if log-valued (a PSD without a jump), else null
    LazySlots<Table> tables_;             // one per wavelength node
};

}  // namespace surfscatter::bsdf
