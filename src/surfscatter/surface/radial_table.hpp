#pragma once
// Internal machinery shared by SelfConvolutionTable and ScatterLobeTable: a family of unit-mass radial densities
// p(zeta) = (1/2pi) H0{f}(zeta), one "row" per f, computed with one FFTLog grid and stored as ln p and its radial CDF
// on a log zeta grid (every 2nd FFTLog output, 128 points per decade), with a flat extension below the stored window
// and a tail above it: p(zeta) = p_top P-hat(zeta)/P-hat(zeta_top) (the m = 1 term dominates the algebraic tails:
// P-hat^{*m} ~ m P-hat, S_g ~ g P-hat), with P-hat and its complementary CDF taken from the statistics' closed forms
// on the stored grid; a power law (slope of the last half decade) only where P-hat underflows.
// Binary (de)serialisation for the disk cache.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "surfscatter/surface/hankel.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface::detail {

struct RadialRow {
    int lo = 0;                       // first stored index on the shared stored grid
    std::vector<double> log_value;    // ln p at stored indices lo, lo+1, ...
    std::vector<double> cdf;          // radial CDF (mass inside) at the same nodes
    double tail_eps = 0.0;            // beyond the window p = c P-hat (1 + eps (zeta/zeta_top)^kappa)
    double tail_kappa = 0.0;
    double tail_slope = -3.0;         // d ln p / d ln zeta beyond the window where P-hat underflows (< -2)
};

struct RadialFamily {
    LogGrid grid;                     // stored zeta grid
    std::vector<RadialRow> rows;
    std::vector<double> log_base;     // ln P-hat on the whole stored grid (closed form of the statistics)
    std::vector<double> log_base_ccdf;  // ln(1 - F) of P-hat on the stored grid

    void set_base(const RadialStatistics& stats);

    double log_value(int row, double log_zeta) const;         // ln p (with extensions)
    double value(int row, double zeta) const;
    double cdf(int row, double zeta) const;
    double inverse_cdf(int row, double u) const;
    // ln zeta bracket [lo, hi] of the row's CDF = u from its nodes (cheap): below the first node the exact inverse
    // (closed form), beyond the last node that node (lo = hi; the caller extends the bracket through the tail).
    void bracket(int row, double u, double& lo, double& hi) const;
};

// The transform set-up for one statistics: an FFTLog grid wide enough for f = F(rho) whose width in r is set by
// `max_exponent` (the largest g or m for which 1 - rho must be resolved), and rho on that grid.
struct TransformSetup {
    std::unique_ptr<FftLogHankel> hankel;
    std::vector<double> rho;   // rho(r_j)
    std::vector<double> base;  // closed-form P-hat(zeta_j) on the output grid
};
TransformSetup make_transform_setup(const RadialStatistics& stats, double max_exponent);

// Transforms f (sampled on setup's r grid; (1/2pi)H0{f} has mass `mass`) into a row normalised by `mass`.
// `tail_weight` c is the asymptotic ratio (1/2pi)H0{f} / P-hat for large zeta (m for rho^m, g for the GHS lobe):
// where the direct transform falls below 1e-11 of its peak (FFTLog round-off floor ~1e-14), the row continues as
// c P-hat + (1/2pi)H0{f - c rho}, whose remainder is computed separately and has no P-hat-sized tail, for as long as
// that remainder is accurate; the row ends when the remainder is negligible (< 1e-10 c P-hat) or inaccurate, and
// the relative remainder eps = p/(c P-hat) - 1 is continued as a power law fitted over the last quarter decade.
RadialRow make_row(const TransformSetup& setup, const std::vector<double>& f, double mass, double tail_weight,
                   const LogGrid& stored);
LogGrid stored_grid(const TransformSetup& setup);

// The family for `key`: from this process's cache, else the disk cache (if it has `rows` rows), else `build()`
// (then written to disk). Thread-safe; families are shared while any table uses them.
std::shared_ptr<const RadialFamily> cached_family(const std::string& key, std::size_t rows,
                                                  const std::function<RadialFamily()>& build);

// Disk cache: a binary file per key under cache_directory(); returns false (and never throws) if absent/corrupt.
// The format version changes whenever the files' layout or the rows' construction does (tables derived from the
// families put it in their own keys).
inline constexpr std::uint32_t kFamilyFormatVersion = 5;
bool load_family(const std::string& key, RadialFamily& family, std::vector<double>& extra);
void save_family(const std::string& key, const RadialFamily& family, const std::vector<double>& extra);
std::filesystem::path cache_file(const std::string& key);

}  // namespace surfscatter::surface::detail
