#pragma once
// The GHS family (full GHS exact, SSA) on a height map's own 2-D spectrum (`--psd measured`, measured_spectrum 2d;
// docs/MODELS.md "Measured 2-D spectrum"), the lobe from surface::SpectrumLobes2d:
//   f_r(i, o) = F(i, o) N(i, lambda) k^2 S_g(zeta),  zeta = k (i_xy + o_xy),  g = (k sigma (cos theta_i + cos theta_o))^2,
// S_g the full lobe (ghs) or the first order (1 - e^{-g}) P-hat (ghs_ssa energy; strict: g_h P-hat with sigma_h, N = 1),
// plus the coherent delta R e^{-g0}, g0 = (2 k sigma cos theta_i)^2. sigma (sigma_rel^2 = sigma_h^2 times the mass of
// P-hat over the visible disc, the disc of radius k about k i_xy) and N (GhsSettings' normalisations: K making the
// albedo R, the disc mass, or 1) depend on the incidence azimuth phi_i as well as theta_i; the periodogram is even,
// so they are pi-periodic in phi_i. Per wavelength node (GhsBsdf's, from kMinWavelength up) and azimuth node
// (kAzimuthNodes uniform over [0, pi)) ln sigma and ln(N / cos^p theta_i) are GhsBsdf's cubics over cos theta_i;
// between azimuth nodes the periodic 4-point Lagrange cubic, evaluated when a table is loaded at kRefinement points
// per interval and read linearly between them (two cubics in cos theta_i per wavelength node instead of four on the
// eval path; it adds at most 3.5e-4 to ln sigma and 7.2e-4 to ln N, MapGhs.RefinedAzimuthsFollowTheCubicThroughTheNodes;
// memory 0.39 MB per wavelength node); between wavelength nodes linear. A table is 64 x
// kAzimuthNodes pairs of visible-disc integrals (sigma: P-hat's lattice sum over the disc; N: the midpoint sum of the
// lobe over the nodes of the finest row lattice it reads; both with rim weights that keep them continuous in the
// incidence, SpectrumLobes2d::disc_cells), built lazily and kept in the disk cache under a key naming the lobes.
// Accuracy (MapGhs.TablesMatchDirectValues, against direct() between the nodes every 3.1 deg of phi_i): sigma within
// 2.7e-3 and N within 3.2e-3 on a Gaussian map, 7.4e-3 and 5.3e-3 on an elliptical one (L_v / L_u = 0.3); sigma_rel is
// a lattice sum, stepped where lattice points cross the disc's rim, which the cubics smooth (48 azimuth nodes only
// halved it, for twice the table cost).
// Wavelengths below kMinWavelength are an Error (the lobes' g range and their lattice's coverage, 2 k there).
// Sampling: the delta with probability e^{-g0}; otherwise zeta from the lobes' tabulated distribution at g0
// (SpectrumLobes2d::sample), mapped to o_xy = zeta / k - i_xy; a draw outside the visible disc is a failed sample, so
// the pdf is the exact sub-probability density pdf(o) = (1 - e^{-g0}) k^2 cos theta_o p(zeta).
#include <array>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/bsdf/ghs.hpp"
#include "surfscatter/bsdf/incidence_tables.hpp"
#include "surfscatter/bsdf/lazy_slots.hpp"
#include "surfscatter/bsdf/model_options.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/surface/spectrum_lobes_2d.hpp"

namespace surfscatter::bsdf {

class MapGhsBsdf final : public Bsdf {
public:
    static constexpr int kAzimuthNodes = 24;        // phi_i over [0, pi), tabulated
    static constexpr int kRefinement = 4;           // refined azimuths per tabulated interval, read linearly
    static constexpr double kMinWavelength = 360;   // nm
    static constexpr double kDiscCells = 64;        // cells per visible disc radius k in the tables' disc integrals

    // ssa: nullopt for the full GHS lobe, else the SSA form (its first-order lobe).
    MapGhsBsdf(std::shared_ptr<const surface::SpectrumLobes2d> lobes, std::optional<SsaForm> ssa,
               material::Conductor material, GhsSettings settings);

    double eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    std::optional<BsdfSample> sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const override;
    double pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    double delta_reflectance(const Vec3& wi, double lambda_nm) const override;
    double delta_probability(const Vec3& wi, double lambda_nm) const override;
    std::string name() const override { return settings_.name; }
    bool isotropic() const override { return false; }

    // Builds (or loads from the disk cache) the tables of every wavelength node that [lambda_lo, lambda_hi] reads,
    // `threads` nodes at a time, with one progress line (percentage, ETA) over them when they are more than about a
    // second's work. A render calls it before its first path: otherwise each node is built inside the render's own
    // progress on first use, twice when two threads ask for it at once.
    void tabulate(double lambda_lo_nm, double lambda_hi_nm, unsigned threads) const;

    const surface::SpectrumLobes2d& lobes() const { return *lobes_; }
    // The roughness used in g (um) and N for incidence wi (local frame), as tabulated.
    double sigma(const Vec3& wi, double lambda_nm) const { return std::exp(lookup(wi, lambda_nm).log_sigma); }
    double normalization(const Vec3& wi, double lambda_nm) const {
        return std::exp(lookup(wi, lambda_nm).log_norm) * norm_power(wi.z);
    }
    // The lobe density at g and zeta (eval without Fresnel, N and k^2).
    double density(double g, Vec2 zeta) const;
    double density(double g, double log_g, Vec2 zeta) const;  // with ln g given
    // sigma and N computed directly for incidence wi: the reference of the tabulation.
    GhsBsdf::Direct direct(const Vec3& wi, double lambda_nm) const;

private:
    using AzimuthTables = std::array<IncidenceTable, kAzimuthNodes>;
    using RefinedTables = std::array<IncidenceTable, kAzimuthNodes * kRefinement>;
    static RefinedTables refine(const AzimuthTables& tables);
    using Incidence = IncidenceLookup;
    Incidence lookup(const Vec3& wi, double lambda_nm) const;
    Incidence interpolate(const Vec3& wi, double lambda_nm) const;  // lookup's body, inlined into eval
    double norm_power(double cos_theta_i) const {
        return settings_.normalization == LobeNormalization::albedo ? cos_theta_i * cos_theta_i : 1.0;
    }
    double eval(const Vec3& wi, const Vec3& wo, double lambda_nm, const Incidence& in) const;
    double pdf(const Vec3& wi, const Vec3& wo, const Incidence& in) const;
    // show_progress: a progress line of its own when the build is more than about a second's work.
    AzimuthTables cached_tables(double lambda_nm, bool show_progress = true) const;
    AzimuthTables build_tables(double lambda_nm, bool show_progress) const;
    const RefinedTables& table(int slot, bool show_progress = true) const;  // wavelength node `slot`'s, on first use
    static double disc_work(double disc_cells) {  // cells of a node's disc integrals
        return disc_cells * kAzimuthNodes * kGhsThetaNodes;
    }

    // The lobes' bins for the visible-disc integrals at wavenumber k: made, and made with the last k asked for kept
    // (direct()'s; build_tables makes its own).
    std::shared_ptr<const surface::SpectrumLobes2d::Bins> make_disc_bins(double k) const;
    std::shared_ptr<const surface::SpectrumLobes2d::Bins> disc_bins(double k) const;
    GhsBsdf::Direct direct(const Vec3& wi, double lambda_nm, const surface::SpectrumLobes2d::Bins& bins) const;

    std::shared_ptr<const surface::SpectrumLobes2d> lobes_;
    mutable std::mutex bins_mutex_;
    mutable std::shared_ptr<const surface::SpectrumLobes2d::Bins> bins_;
    mutable double bins_k_ = 0;
    std::optional<SsaForm> ssa_;
    material::Conductor material_;
    GhsSettings settings_;
    LazySlots<RefinedTables> tables_;  // one per wavelength node
};

// The lobes of a map's periodogram for every g these models reach at wavelengths >= MapGhsBsdf::kMinWavelength
// (g <= (2 k sigma_h)^2 with a margin for the tables' interpolation of sigma).
std::shared_ptr<const surface::SpectrumLobes2d> map_lobes(const surface::Psd2d& spectrum);

}  // namespace surfscatter::bsdf
