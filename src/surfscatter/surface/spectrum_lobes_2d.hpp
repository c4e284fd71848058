#pragma once
// The full GHS scatter lobe of a height map's own 2-D spectrum (`--psd measured`, measured_spectrum 2d; docs/SURFACE.md
// "The 2-D measured lobes"): the radial ScatterLobeTable's lobe, but on the periodogram itself, not its ring average:
//   S_g(zeta) = e^{-g} sum_{m>=1} g^m/m! P-hat^{*m}(zeta) = (1/4 pi^2) FT{e^{-g (1 - rho(r))} - e^{-g}}(zeta),
// of mass 1 - e^{-g}, tabulated as its unit-mass shape s_g = S_g / (1 - e^{-g}).
// Construction:
// 1. P-hat = the periodogram (MapStatistics::spectrum(): its window, its DC bin continued from the lowest ring) over
//    its lattice sum, which is sigma_h^2 here (the whole lattice, its corners beyond the Nyquist disc included; the
//    ring route sums the disc). A masked estimate's bins below zero (psd_estimate.hpp) are set to 0 and the positive
//    bins of their ring scaled to keep its sum (a ring whose sum is not positive is 0, as the ring route skips it):
//    e^{g rho} is a positive lobe only for a spectrum that is positive (frt-2's map failed on them at 1.6e-4 of the
//    peak; SpectrumLobes2d.MaskedSpectrumKeepsItsRingsAndLobesArePositive).
//    The lattice's Nyquist bins of an even side are split half and half between +Nyquist and -Nyquist, so that every
//    tabulated lobe is even (S(-zeta) = S(zeta)). Beyond the lattice P-hat is 0, as the ring route's roll-off
//    (zeta^-200 beyond Nyquist) makes it in effect: nothing beyond what the map holds enters the first order.
// 2. rho(r) = sum P-hat e^{i zeta r} dzeta^2 by an inverse FFT of the spectrum zero-padded p-fold (band-limited
//    interpolation onto a lattice p times finer): p the smallest integer with p * Nyquist >= kCoverage (2 k at
//    360 nm), at most kMaxLattice / (larger side). e^{g rho} then carries the self-convolutions, which spread beyond
//    Nyquist (order m reaches m Nyquist), out to p * Nyquist; what an order would put beyond p * Nyquist folds back
//    (the lattice is periodic): edge_fraction() reports the largest share of any g > 0 row's mass in the outer quarter
//    of its lattice, the measure of that folding, and the models pass it on in their notes.
// 3. Rows: g -> 0 (P-hat itself) and kRowsPerDecade log-spaced g from kMinG up to the g_max given; those at
//    g >= rough_limit_g() in the rough-surface limit (below), the others in full. For each g in full,
//    f = e^{-g (1 - rho)} - e^{-g} on the fine lattice cropped to the square window outside which f < kCropValue f(0)
//    (the whole lattice for small g: f ~ g rho there; a few correlation lengths for large g, where the lobe is wide
//    and its zeta grid may be coarse), transformed (r2c FFT); the result is cropped to the square holding all but
//    kCropMass of the row's mass and averaged over odd s x s blocks of bins so that at most kMaxCells per axis
//    remain (s = 1, every bin of the map's spectrum kept, for maps up to kMaxCells per side at g -> 0). Round-off
//    below zero (below 1e-12 of a row's peak) is set to 0; each row is scaled to unit mass.
// Lookup: bilinear in zeta on a row's nodes (0 beyond its outermost nodes), cubic Lagrange in ln g over 4 rows (one-
// sided at the ends; its undershoot below 0 next to a row's edge read as 0), linear in g between the g -> 0 row and
// kMinG.
// Accuracy (SpectrumLobes2d.MatchesDirectPoissonSeriesOfConvolutions, against direct 2-D linear convolutions of a 32^2
// periodogram summed in the Poisson series, written in the test): at the lattice's nodes |S_g - direct| below 5e-4 of
// the lobe's peak for g 0.01 .. 5 on and between rows (measured 1e-9 on rows, 1.8e-4 between them: the cubic in ln g
// dominates; linear, it was 6e-3), every row's mass within 1e-8 of 1 - e^{-g} (the crops drop below kCropMass).
// Building: one FFT of the fine lattice for rho plus one per row (the large-g rows' windows are small): for a
// 1024^2 map see docs/PERFORMANCE.md ("2-D measured lobes"). Memory: up to kMaxCells^2 doubles per row (plus the
// same for its sampling CDF once a row is sampled).
// Sampling: the row pair of g (or row 0 and the first row) as a mixture with linear weights in ln g (in g below
// kMinG), within a row a bilinear cell by its CDF and the point inside it from the bilinear density (its marginal in
// x, then y given x, both inverted in closed form); the pdf is that mixture of the rows' bilinear shapes (each over its
// own cell sum), exact for what is drawn and continuous (the eval's cubic in ln g is not the sampler's).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/psd_estimate.hpp"

namespace surfscatter::surface {

class SpectrumLobes2d {
public:
    static constexpr double kMinG = 1e-3;
    static constexpr int kRowsPerDecade = 12;
    static constexpr std::size_t kMaxCells = 383;       // per axis of a stored row
    static constexpr std::size_t kMaxLattice = 2048;    // per axis of the fine lattice of rho
    static constexpr double kCoverage = 4.0 * kPi / 0.36;  // rad/um: 2 k at 360 nm
    static constexpr double kCropValue = 1e-10;
    static constexpr double kCropMass = 1e-9;
    // The rough-surface limit (rows at g >= rough_limit_g()): its estimated error at the lobe's peak, relative.
    static constexpr double kRoughTolerance = 0.01;
    static constexpr int kGaussNodesPerSigma = 6;     // node spacing of a limit row, per standard deviation and axis
    static constexpr double kGaussSigmas = 7.5;       // its extent (e^{-28}: below kCropMass)

    // The lobes of `spectrum` (a periodogram, estimate_psd()) for g in [0, g_max]; rough_limit false computes every
    // row in full (the reference of the limit's accuracy). Error if its lattice sum is not positive or g_max not in
    // (0, 1e7].
    SpectrumLobes2d(const Psd2d& spectrum, double g_max, bool rough_limit = true);

    double sigma_h() const { return sigma_h_; }                // sqrt of the periodogram's lattice sum, um
    double g_max() const { return g_max_; }
    double eval(double g, Vec2 zeta) const;                    // S_g(zeta), um^2; g in [0, g_max] (else Error)
    double shape(double g, Vec2 zeta) const;                   // s_g = S_g / (1 - e^{-g}), unit mass
    // The same with ln g given (ln 0 = -inf): a caller that has ln g before g (MapGhsBsdf::eval) shortens the chain
    // from its lookup to the rows' loads.
    double eval(double g, double log_g, Vec2 zeta) const;
    double shape(double g, double log_g, Vec2 zeta) const;
    double first_order(Vec2 zeta) const;                       // P-hat(zeta) (unit mass): the g -> 0 row
    // The finest node spacing (rad/um) of the rows that g in [g_lo, g_hi] reads.
    double finest_spacing(double g_lo, double g_hi) const;
    // The rows' unit-mass shapes as masses on the square grid of spacing h through 0 (cells -half .. half per axis,
    // half = ceil(extent / h)), for product integrals over a disc (MapGhsBsdf's tables; docs/MODELS.md "Measured 2-D
    // spectrum"): along an axis on which a row's nodes are finer than h their masses (value times spacing) are summed
    // into the cell holding them, along any other its linear interpolant is taken at the cell's centre times h (per
    // axis, so that a row's bilinear reading is kept where it is coarse and its every node where it is fine). Only
    // the rows that some g in [0, g_hi] reads are made; the others are left empty.
    struct Bins {
        double h = 0;
        long half = 0;
        std::vector<std::vector<double>> mass;  // per row: [(j + half) * (2 half + 1) + (i + half)]
    };
    Bins bins(double h, double extent, double g_hi) const;
    // s_g's mass in cell `index` of `bins` (first_order_only: P-hat's), over the rows as shape() reads them.
    double binned_shape(const Bins& bins, std::size_t index, double g, bool first_order_only) const;
    // Sum over the cells of `bins` within `radius` of `centre` of f(index, the cell's centre), each weighted by the
    // share of its cell inside the disc (a linear ramp over one cell): continuous in centre and radius.
    template <class F>
    double disc_cells(const Bins& bins, Vec2 centre, double radius, F&& f) const;
    // A zeta drawn from s_g (first_order_only: from P-hat), and the density of that draw at zeta (1/um^2^-1).
    Vec2 sample(double g, bool first_order_only, double u_row, Vec2 u) const;
    double sample_density(double g, bool first_order_only, Vec2 zeta) const;

    double edge_fraction() const { return edge_fraction_; }   // see 2. above (rows in full only)
    // The spectrum's bins below zero (a masked estimate's scatter), set to 0: their |sum| over the positive bins' sum.
    double clipped_fraction() const { return clipped_fraction_; }
    // The rough-surface limit: rows with g >= rough_limit_g() are the Gaussian of covariance g M2 (M2 = slope_moment(),
    // the unit periodogram's second moment: the slope covariance over sigma_h^2), the lobe's limit as g -> inf where
    // e^{-g (1 - rho)} -> e^{-g r.M2.r / 2}. Its relative error at the peak is the Edgeworth term of the compound
    // Poisson sum, K / (8 g) with K = E[(zeta.M2^-1.zeta)^2] over P-hat (kurtosis()); the switch is where that is
    // kRoughTolerance (+inf when rough_limit is false or K is not finite).
    double rough_limit_g() const { return rough_limit_g_; }
    std::array<double, 3> slope_moment() const { return moment_; }  // M2: xx, xy, yy (rad/um)^2
    double kurtosis() const { return kurtosis_; }
    std::size_t rough_rows() const { return rough_rows_; }          // rows made in the limit
    std::size_t padding() const { return padding_; }          // p
    std::size_t rows() const { return rows_.size(); }
    double row_g(std::size_t row) const { return row_g_[row]; }  // 0 for row 0
    double row_mass_before_scaling(std::size_t row) const { return rows_[row].raw_mass; }
    const std::string& key() const { return key_; }            // names the spectrum and the construction

    struct Row {
        double hx = 0, hy = 0;     // node spacing, rad/um
        double inv_hx = 0, inv_hy = 0;
        long half_x = 0, half_y = 0;  // nodes -half .. half per axis
        double raw_mass = 0;       // the row's mass before scaling to 1 (what the crops left, in units of 1 - e^{-g})
        std::vector<double> value; // unit-mass shape at the nodes, [(j + half_y) * (2 half_x + 1) + (i + half_x)]
        double at(Vec2 zeta) const;                     // bilinear
    };

private:
    struct Mixture { std::size_t a, b; double wa, wb; };
    // The cubic in ln g (g >= kMinG): its rows first + 1 .. first + 4 and their weights.
    struct Cubic { long first; std::array<double, 4> w; };
    Cubic cubic(double log_g) const;
    Mixture mixture(double g, bool first_order_only) const;
    const std::vector<double>& cdf(std::size_t row) const;

    double sigma_h_ = 0, g_max_ = 0, edge_fraction_ = 0, clipped_fraction_ = 0, rough_limit_g_ = HUGE_VAL, kurtosis_ = 0;
    std::array<double, 3> moment_{};
    std::size_t rough_rows_ = 0;
    std::size_t padding_ = 1;
    Psd2d spectrum_;                 // normalised to unit lattice sum
    std::vector<Row> rows_;
    std::vector<double> row_g_;
    std::vector<char> shared_lattice_;  // [first]: rows first + 1 .. first + 4 (a cubic's stencil) share one lattice
    std::string key_;
    mutable std::vector<std::vector<double>> cdfs_;
    mutable std::unique_ptr<std::once_flag[]> cdf_once_;
};

template <class F>
double SpectrumLobes2d::disc_cells(const Bins& bins, Vec2 centre, double radius, F&& f) const {
    const double h = bins.h, outer = radius + 0.5 * h;
    const long n = 2 * bins.half + 1;
    const long j0 = std::max(-bins.half, long(std::ceil((centre.y - outer) / h)));
    const long j1 = std::min(bins.half, long(std::floor((centre.y + outer) / h)));
    const long i0 = std::max(-bins.half, long(std::ceil((centre.x - outer) / h)));
    const long i1 = std::min(bins.half, long(std::floor((centre.x + outer) / h)));
    double sum = 0;
    for (long j = j0; j <= j1; ++j) {
        const double y = double(j) * h, dy = y - centre.y;
        for (long i = i0; i <= i1; ++i) {
            const double x = double(i) * h, dx = x - centre.x;
            const double w = std::clamp(0.5 + (radius - std::sqrt(dx * dx + dy * dy)) / h, 0.0, 1.0);
            if (w > 0) sum += w * f(std::size_t((j + bins.half) * n + (i + bins.half)), Vec2(x, y));
        }
    }
    return sum;
}

}  // namespace surfscatter::surface
