#pragma once
// The GHS family (GhsBsdf: full GHS exact or refit, SSA) on elliptical statistics (surface/elliptical_statistics.hpp,
// THEORY 7.1, docs/MODELS.md "Anisotropic models"): any isotropic ScatterCore built on the radial statistics serves,
// read at the stretched radius (Fourier scaling: P-hat^{*m}(zeta) = s P-hat_radial^{*m}(|(zeta_u, s zeta_v)|) for
// every order m, so S_g(zeta) = s S_g,radial(|(zeta_u, s zeta_v)|), s = LV / LU):
//   f_r(i, o) = F(i, o) N(i, lambda) k^2 s core.density(g, |(zeta_u, s zeta_v)|),  zeta = k (i_xy + o_xy),
//   g = (k sigma (cos theta_i + cos theta_o))^2, plus the coherent delta R e^{-g0}, g0 = (2 k sigma cos theta_i)^2.
// sigma (sigma_rel^2 = sigma_h^2 times the mass of P-hat over the visible disc, the disc of radius k about k i_xy in
// the zeta plane; P-hat is even, so the disc about -k i_xy holds the same) and N (GhsBsdf's normalisations) now
// depend on the incidence azimuth relative to the lay, phi_r = phi_i - A, through c = cos 2 phi_r only: the surface is
// symmetric under phi_r -> -phi_r and phi_r -> phi_r + pi, and an even pi-periodic smooth function of phi_r is a
// smooth function of cos 2 phi_r. Per wavelength node (GhsBsdf's) and per azimuth node (kAzimuthNodes over phi_r in
// [0, 90] deg, 3.5 deg apart at the lay and its normal, 6.4 deg at 45 deg: nodes uniform in cos 2 phi_r left 20.7 deg
// between the lay and the next, and at grazing incidence, where the rim cuts the lobe's narrow direction, sigma was
// 3.8e-3 low at 85 deg; 13 nodes uniform in phi_r, 5.4e-3 at 89.9 deg) ln sigma and ln(N / cos^p theta_i) are
// GhsBsdf's cubics over cos theta_i; between azimuth nodes the 4-point Lagrange cubic in the graded coordinate, its
// stencil reflected at 0 and 90 deg (both even), between wavelength nodes linear. A table is 64 x 21 pairs of
// visible-disc integrals, both over the rays of the stretched plane w = (zeta_u, s zeta_v) / k from the specular
// point, where the lobe is a function of |w| and of g alone and the disc an ellipse (adaptive Gauss-Kronrod over the
// ray angle, each quarter graded toward the ray where grazing incidence brings the horizon close): sigma from the
// radial CDF at each ray's end, N from a fixed 32-point rule along each ray (24 in ln |w| for the lobe, 8 at the
// horizon); built lazily and kept in the disk cache under a key naming the elliptical statistics (LV and A included),
// the core and the settings; ~0.15 CPU s per wavelength node for photo-setup's plate with 9 azimuth nodes (bench_bsdf
// BM_ghs_tables/1; 21 cost ~21/9 of that; a render touches ~45 nodes once; the disk cache keeps them).
// Accuracy (AnisotropicGhs.TablesMatchDirectQuadrature, against Gauss-Legendre over the disc written in the test):
// sigma within 1e-3 and N within 3e-3 of their direct values at (theta_i, phi_r) between the nodes for s = 0.25 and 4
// (measured 1.5e-5 and 1.1e-4; the direct values themselves within 1e-4, measured 6.8e-6, and at normal and grazing
// incidence, 88.5 and 89.7 deg, for photo-setup's plate too: 1.5e-5, AnisotropicGhs.DirectValuesHoldAtGrazingIncidence);
// sigma within 1e-3 of the direct value at every azimuth (0.5 deg steps) up to 89.9 deg incidence, photo-setup's
// plate at 550 nm and a wide lobe (measured 6.6e-4 at 89.9 deg, 1.5 deg from the lay;
// AnisotropicGhs.SigmaHoldsAtEveryAzimuthUpToGrazing).
// Sampling: the delta with probability e^{-g0}; otherwise the core's radius at g* = g0 in the stretched plane
// (|w| <= k (1 + sin theta_i) max(1, s), w = (zeta_u, s zeta_v)), a uniform azimuth there, mapped back to zeta; a draw
// outside the visible disc is a failed sample (nothing returned), so the pdf is the exact sub-probability density
//   pdf(o) = (1 - e^{-g0}) s k^2 cos theta_o p_core(|w|).
// The core's PSD may jump (the two-scale micro part: SharpCutStatistics, whose cut is a circle in the stretched plane,
// an ellipse in zeta): eval and the sampler are then exact as for the isotropic micro lobe (the core adds the first
// order at the stretched radius), and N's ray rule is applied on each side of the jump (the micro lobe's albedo is R
// within 2.6e-5, TwoScaleElliptical.AlbedoAtMostROverEveryIncidenceAzimuth in tests/bsdf/test_two_scale_elliptical.cpp,
// against quadrature written there that splits every ray at the ellipse).
#include <array>
#include <functional>
#include <memory>
#include <string>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/bsdf/ghs.hpp"
#include "surfscatter/bsdf/incidence_tables.hpp"
#include "surfscatter/bsdf/lazy_slots.hpp"
#include "surfscatter/bsdf/scatter_core.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/surface/elliptical_statistics.hpp"

namespace surfscatter::bsdf {

class AnisotropicGhsBsdf final : public Bsdf {
public:
    static constexpr int kAzimuthNodes = 21;  // over phi_r in [0, 90] deg, graded toward 0 and 90 (.cpp)

    // `core` made on stats->radial_ptr() (ExactScatterCore, RefitScatterCore or FirstOrderCore).
    AnisotropicGhsBsdf(std::shared_ptr<const surface::EllipticalStatistics> stats,
                       std::shared_ptr<const ScatterCore> core, material::Conductor material, GhsSettings settings);

    double eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    std::optional<BsdfSample> sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const override;
    double pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    WavelengthValues eval_packet(const Vec3& wi, const Vec3& wo, const WavelengthValues& lambda_nm,
                                 WavelengthValues* pdf) const override;
    double delta_reflectance(const Vec3& wi, double lambda_nm) const override;
    double delta_probability(const Vec3& wi, double lambda_nm) const override;
    std::string name() const override { return settings_.name; }
    bool isotropic() const override { return false; }

    const surface::EllipticalStatistics& statistics() const { return *stats_; }
    // The roughness used in g (um) and the lobe normalisation N for incidence wi (local frame), as tabulated.
    double sigma(const Vec3& wi, double lambda_nm) const { return std::exp(lookup(wi, lambda_nm).log_sigma); }
    double normalization(const Vec3& wi, double lambda_nm) const {
        return std::exp(lookup(wi, lambda_nm).log_norm) * norm_power(wi.z);
    }
    // The lobe density s S_g,radial(|(zeta_u, s zeta_v)|) at exponent g and zeta (rad/um, local frame): eval's lobe
    // without Fresnel, normalisation and k^2.
    double lobe_density(double g, Vec2 zeta_xy) const {
        return stretch_ * core_->density(g, stats_->stretched_radius(zeta_xy));
    }
    // Both computed directly for incidence wi (visible-disc integrals, ~0.3 ms): the reference of the tabulation.
    GhsBsdf::Direct direct(const Vec3& wi, double lambda_nm) const;

private:
    using AzimuthTables = std::array<IncidenceTable, kAzimuthNodes>;
    using Incidence = IncidenceLookup;
    Incidence lookup(const Vec3& wi, double lambda_nm) const;
    Incidence lookup(const Vec3& wi, double lambda_nm, double k) const;
    double norm_power(double cos_theta_i) const {
        return settings_.normalization == LobeNormalization::albedo ? cos_theta_i * cos_theta_i : 1.0;
    }
    // |(zeta_u, s zeta_v)| / k for q = i_xy + o_xy.
    double stretched(double qx, double qy) const {
        const Vec2 uv = stats_->to_lay({qx, qy});
        return std::sqrt(uv.x * uv.x + stretch2_ * uv.y * uv.y);
    }
    double eval(const Vec3& wi, const Vec3& wo, double lambda_nm, const Incidence& in, double log_cosine_sum,
                double log_stretched2) const;
    double pdf(const Vec3& wi, const Vec3& wo, const Incidence& in) const;
    double stretched_zeta_max(const Vec3& wi, double k) const;
    AzimuthTables cached_tables(double lambda_nm) const;
    AzimuthTables build_tables(double lambda_nm) const;
    // The rays of the stretched plane from the specular point to the edge of the visible disc (the .cpp says more).
    struct DiscRays {
        struct Ray {
            double a, q_max, rho_max;  // |w| / |q| along the ray; where it leaves the disc, in |q| and in |w|
        };
        DiscRays(const AnisotropicGhsBsdf& bsdf, const Vec3& wi);
        Ray at(double psi) const;
        double integrate(const std::function<double(const Ray&)>& f, double rel_tol, double abs_scale) const;
        double stretch, sin_i, cos2_i;
        Vec2 incidence;  // i_xy / sin theta_i in lay components
        std::array<double, 5> edges;
    };
    static constexpr int kLobeNodes = 24, kHorizonNodes = 8;  // per ray, scatter_mass
    double visible_disc_mass(const Vec3& wi, double k) const;  // sigma_rel^2 / sigma_h^2
    double scatter_mass(const Vec3& wi, double k, double sigma) const;  // the lobe's integral over the visible disc

    std::shared_ptr<const surface::EllipticalStatistics> stats_;
    std::shared_ptr<const ScatterCore> core_;
    material::Conductor material_;
    GhsSettings settings_;
    double stretch_, stretch2_;
    const surface::ScatterLobeTable* log_native_;  // the exact core's log-valued table, else null
    LazySlots<AzimuthTables> tables_;               // one per wavelength node
};

}  // namespace surfscatter::bsdf
