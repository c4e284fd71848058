#pragma once
// The GHS family of BRDFs (THEORY 1): a coherent specular delta R(theta_i) e^{-g0} plus a scattered lobe
//   f_r(i, o) = F(i, o) * N(theta_i, lambda) * k^2 * core.density(g(theta_i, theta_o), k |i_xy + o_xy|),
//   g = (k sigma (cos theta_i + cos theta_o))^2,  g0 = g(theta_i, theta_i),
// where sigma is the relevant roughness sigma_rel(theta_i, lambda) or sigma_h, F the Fresnel factor
// (incident / half / rr), and N the lobe normalisation: K(theta_i, lambda) making the directional albedo exactly R
// (full GHS, THEORY 1.1 eq 20, and the SSA energy form), sigma_h^2 / sigma_rel^2 (the visible-disc mass) or 1.
// ln sigma and N are tabulated per wavelength node (2 % apart over [kMinWavelength, kMaxWavelength]; other wavelengths
// are an Error) over cos theta_i (52 nodes to 89.5 deg, denser toward grazing), built lazily, read without a lock once
// built, and interpolated bilinearly in (cos theta_i, lambda) between nodes found by NodeAxis (no log, no acos). eval
// hands ln g and ln zeta to the core (the exact core's table is log-spaced in both): two logarithms per call, taken
// before the lookup so that they overlap with it.
// Sampling: the delta with probability e^{-g0}; otherwise |zeta| from the core at g* = g0 and the azimuth over the
// visible wedge; the pdf is exact (wedge_pdf).
#include <array>
#include <cmath>
#include <memory>
#include <string>

#include "surfscatter/bsdf/bsdf.hpp"
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
    static constexpr double kMinWavelength = 0.1;  // nm
    static constexpr double kMaxWavelength = 1e8;  // nm
    static constexpr int kThetaNodes = 52;         // incidence nodes of the sigma / N tables

    GhsBsdf(std::shared_ptr<const surface::RadialStatistics> stats, std::shared_ptr<const ScatterCore> core,
            material::Conductor material, GhsSettings settings);

    double eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    std::optional<BsdfSample> sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const override;
    double pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    double delta_reflectance(const Vec3& wi, double lambda_nm) const override;
    double delta_probability(const Vec3& wi, double lambda_nm) const override;
    std::string name() const override { return settings_.name; }

    // The roughness used in g (um) and the lobe normalisation N at (theta_i, lambda), as tabulated.
    double sigma(double cos_theta_i, double lambda_nm) const {
        return std::exp(lookup(cos_theta_i, lambda_nm).log_sigma);
    }
    double normalization(double cos_theta_i, double lambda_nm) const { return lookup(cos_theta_i, lambda_nm).norm; }
    // Both computed directly at (theta_i, lambda), as at the table's nodes (an integral over the visible disc, ~1 ms):
    // the reference for the tabulation's accuracy.
    struct Direct {
        double sigma, norm;
    };
    Direct direct(double theta_i, double lambda_nm) const;
    // The core lobe without Fresnel and normalisation: k^2 density(g, zeta) (symmetric in wi <-> wo when sigma is).
    double core_lobe(const Vec3& wi, const Vec3& wo, double lambda_nm, double sigma_um) const;

private:
    struct Node { double log_sigma, norm; };
    using Table = std::array<Node, kThetaNodes>;  // over theta_i
    struct Incidence { double k, log_sigma, norm; };  // k in rad/um
    Incidence lookup(double cos_theta_i, double lambda_nm) const;
    static double specular_exponent(const Incidence& in, double cos_theta_i);  // g0 = (2 k sigma cos theta_i)^2
    struct LobeLogs {  // ln g - 2 ln sigma and ln zeta of a direction pair
        LobeLogs(const Vec3& wi, const Vec3& wo, double k);
        double log_g_over_sigma2, log_zeta;
    };
    double density(const LobeLogs& logs, double log_sigma) const;
    Table build_table(double lambda_nm) const;
    double scatter_mass(double theta_i, double lambda_nm, double sigma_um) const;  // integral of density over disc
    double fresnel(const Vec3& wi, const Vec3& wo, double lambda_nm) const;

    std::shared_ptr<const surface::RadialStatistics> stats_;
    std::shared_ptr<const ScatterCore> core_;
    material::Conductor material_;
    GhsSettings settings_;
    const ExactScatterCore* exact_;  // core_ if it is the exact one (called directly), else null
    LazySlots<Table> tables_;        // one per wavelength node
};

}  // namespace surfscatter::bsdf
