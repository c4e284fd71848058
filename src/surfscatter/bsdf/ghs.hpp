#pragma once
// The GHS family of BRDFs (THEORY 1): a coherent specular delta R(theta_i) e^{-g0} plus a scattered lobe
//   f_r(i, o) = F(i, o) * N(theta_i, lambda) * k^2 * core.density(g(theta_i, theta_o), k |i_xy + o_xy|),
//   g = (k sigma (cos theta_i + cos theta_o))^2,  g0 = g(theta_i, theta_i),
// where sigma is the relevant roughness sigma_rel(theta_i, lambda) or sigma_h, F the Fresnel factor
// (incident / half / rr), and N the lobe normalisation: K(theta_i, lambda) making the directional albedo exactly R
// (full GHS, THEORY 1.1 eq 20, and the SSA energy form), sigma_h^2 / sigma_rel^2 (the visible-disc mass) or 1.
// sigma and N are tabulated per wavelength node (log-spaced, 2 %) over theta_i (46 nodes to 89.5 deg, denser toward grazing), built lazily,
// thread-safe, and interpolated linearly in theta_i and log lambda.
// Sampling: the delta with probability e^{-g0}; otherwise |zeta| from the core at g* = g0 and the azimuth over the
// visible wedge; the pdf is exact (wedge_pdf).
#include <map>
#include <memory>
#include <shared_mutex>
#include <string>
#include <vector>

#include "surfscatter/bsdf/bsdf.hpp"
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
    GhsBsdf(std::shared_ptr<const surface::RadialStatistics> stats, std::shared_ptr<const ScatterCore> core,
            material::Conductor material, GhsSettings settings);

    double eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    std::optional<BsdfSample> sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const override;
    double pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    double delta_reflectance(const Vec3& wi, double lambda_nm) const override;
    double delta_probability(const Vec3& wi, double lambda_nm) const override;
    std::string name() const override { return settings_.name; }

    // The roughness used in g (um) and the lobe normalisation N at (theta_i, lambda), as tabulated.
    double sigma(double cos_theta_i, double lambda_nm) const { return lookup(cos_theta_i, lambda_nm).sigma; }
    double normalization(double cos_theta_i, double lambda_nm) const { return lookup(cos_theta_i, lambda_nm).norm; }
    // The core lobe without Fresnel and normalisation: k^2 density(g, zeta) (symmetric in wi <-> wo when sigma is).
    double core_lobe(const Vec3& wi, const Vec3& wo, double lambda_nm, double sigma_um) const;

private:
    struct Node { double sigma, norm; };
    struct Table { std::vector<Node> nodes; };  // over theta_i
    Node lookup(double cos_theta_i, double lambda_nm) const;
    const Table& table(int lambda_node) const;
    Table build_table(double lambda_nm) const;
    double scatter_mass(double theta_i, double lambda_nm, double sigma_um) const;  // integral of density over disc
    double fresnel(const Vec3& wi, const Vec3& wo, double lambda_nm) const;

    std::shared_ptr<const surface::RadialStatistics> stats_;
    std::shared_ptr<const ScatterCore> core_;
    material::Conductor material_;
    GhsSettings settings_;
    mutable std::shared_mutex mutex_;
    mutable std::map<int, std::unique_ptr<Table>> tables_;
};

}  // namespace surfscatter::bsdf
