#include "surfscatter/surface/spectrum_lobes_2d.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstring>
#include <numbers>

#include <fftw3.h>
#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/math/fast_math.hpp"
#include "surfscatter/math/lagrange.hpp"
#include "surfscatter/heightmap/fftw_planner.hpp"
#include "surfscatter/heightmap/height_map_fft.hpp"

namespace surfscatter::surface {

namespace {

constexpr std::uint32_t kVersion = 2;  // of the construction, in key()

// A real function on a full, centred lattice: nodes -half_x .. half_x by -half_y .. half_y, spacing dzx, dzy.
struct Centred {
    long half_x = 0, half_y = 0;
    double dzx = 0, dzy = 0;
    std::vector<double> v;
    double& at(long i, long j) { return v[std::size_t((j + half_y) * (2 * half_x + 1) + (i + half_x))]; }
    double at(long i, long j) const { return v[std::size_t((j + half_y) * (2 * half_x + 1) + (i + half_x))]; }
};

// The full plane of a half-plane (r2c) layout value(kx, ky) of an n_x x n_y lattice, kx in [0, n_x/2]: the point
// (-kx, -ky) mirrors (kx, ky); a Nyquist bin of an even side (the same lattice point at +- n/2) is split half and half
// between both, so that the result is even.
// Into `c`, whose storage is reused (the rows' lattices are up to 2048^2: a fresh one per row cost a third of a
// build in page faults).
template <class Value>
void centred_plane(std::size_t nx, std::size_t ny, double dzx, double dzy, Value value, Centred& c) {
    c.half_x = long(nx / 2);
    c.half_y = long(ny / 2);
    c.dzx = dzx;
    c.dzy = dzy;
    c.v.resize(std::size_t((2 * c.half_x + 1) * (2 * c.half_y + 1)));  // every element written below
    const auto wrap = [](long k, std::size_t n) { return std::size_t(((k % long(n)) + long(n)) % long(n)); };
    const double edge_x = nx % 2 == 0 ? 0.5 : 1.0;
    for (long j = -c.half_y; j <= c.half_y; ++j) {
        const double fy = ny % 2 == 0 && std::abs(j) == c.half_y ? 0.5 : 1.0;
        const std::size_t plus = wrap(j, ny), minus = wrap(-j, ny);  // ky of the nodes i >= 0 and i < 0
        double* row = &c.at(0, j);
        for (long i = -c.half_x; i < 0; ++i) row[i] = fy * value(std::size_t(-i), minus);
        for (long i = 0; i <= c.half_x; ++i) row[i] = fy * value(std::size_t(i), plus);
        if (c.half_x > 0) {
            row[-c.half_x] *= edge_x;
            row[c.half_x] *= edge_x;
        }
    }
}

// Chebyshev ring (max(|i|, |j|)) of a node.
long ring_of(long i, long j) { return std::max(std::abs(i), std::abs(j)); }

// The stored row of a centred lattice: cropped to the square of Chebyshev radius D outside which at most kCropMass of
// its |mass| lies, averaged over odd s x s blocks so that at most kMaxCells nodes per axis remain, round-off below 0
// set to 0, scaled to unit mass; `mass` is the lobe's exact mass (1 - e^{-g}, or 1) for raw_mass. `edge` gets the
// share of the mass in the outer quarter of the lattice.
SpectrumLobes2d::Row make_row(const Centred& c, double mass, double& edge) {
    const long rings = std::max(c.half_x, c.half_y) + 1;
    std::vector<double> ring_mass(std::size_t(rings), 0.0);
    double total = 0, outer = 0, peak = 0;
    for (long j = -c.half_y; j <= c.half_y; ++j)
        for (long i = -c.half_x; i <= c.half_x; ++i) {
            const double a = std::abs(c.at(i, j));
            ring_mass[std::size_t(ring_of(i, j))] += a;
            total += a;
            peak = std::max(peak, c.at(i, j));
            if (4 * std::abs(i) > 3 * c.half_x || 4 * std::abs(j) > 3 * c.half_y) outer += a;
        }
    edge = total > 0 ? outer / total : 0.0;
    long radius = rings - 1;
    for (double tail = 0; radius > 0 && tail + ring_mass[std::size_t(radius)] <= SpectrumLobes2d::kCropMass * total;
         --radius)
        tail += ring_mass[std::size_t(radius)];
    const long dx = std::min(radius, c.half_x), dy = std::min(radius, c.half_y);
    auto nodes = [](long d, long s) { return 2 * ((d + s - 1) / s) + 1; };
    long s = 1;
    while (nodes(dx, s) > long(SpectrumLobes2d::kMaxCells) || nodes(dy, s) > long(SpectrumLobes2d::kMaxCells)) s += 2;
    SpectrumLobes2d::Row row;
    row.half_x = (dx + s - 1) / s;
    row.half_y = (dy + s - 1) / s;
    row.hx = double(s) * c.dzx;
    row.hy = double(s) * c.dzy;
    row.inv_hx = 1.0 / row.hx;
    row.inv_hy = 1.0 / row.hy;
    row.value.assign(std::size_t((2 * row.half_x + 1) * (2 * row.half_y + 1)), 0.0);
    const long h = (s - 1) / 2;
    // An FFT's round-off is relative to the transform's total mass, not its peak: a broad lobe on a 2048^2 lattice
    // (tmd-1: -4.2e-10 against a peak of 353) leaves round-off above 1e-12 of its peak.
    const double floor = 1e-12 * std::max(peak, total);
    double sum = 0;
    for (long j = -row.half_y; j <= row.half_y; ++j)
        for (long i = -row.half_x; i <= row.half_x; ++i) {
            double block = 0;
            for (long b = std::max(j * s - h, -c.half_y); b <= std::min(j * s + h, c.half_y); ++b)
                for (long a = std::max(i * s - h, -c.half_x); a <= std::min(i * s + h, c.half_x); ++a)
                    block += c.at(a, b);
            block /= double(s * s);
            if (block < 0) {
                if (block < -floor) fail("2-D lobe row: value {} below zero beyond round-off (peak {})", block, peak);
                block = 0;
            }
            row.value[std::size_t((j + row.half_y) * (2 * row.half_x + 1) + (i + row.half_x))] = block;
            sum += block;
        }
    const double row_mass = sum * row.hx * row.hy;
    if (!(row_mass > 0)) fail("2-D lobe row without mass");
    row.raw_mass = row_mass / mass;
    for (double& v : row.value) v /= row_mass;
    return row;
}

// FFTW plans, destroyed under the planner's lock.
struct PlanGuard {
    fftw_plan plan;
    explicit PlanGuard(fftw_plan p) : plan(p) {
        if (!plan) fail("FFTW could not create a plan");
    }
    ~PlanGuard() {
        std::lock_guard lock(heightmap::fftw_planner_mutex());
        fftw_destroy_plan(plan);
    }
    PlanGuard(const PlanGuard&) = delete;
    PlanGuard& operator=(const PlanGuard&) = delete;
};

std::size_t power_of_two_at_least(std::size_t n) {
    std::size_t p = 1;
    while (p < n) p *= 2;
    return p;
}

std::uint64_t fnv1a(const void* data, std::size_t bytes, std::uint64_t h = 1469598103934665603ull) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

}  // namespace

double SpectrumLobes2d::Row::at(Vec2 zeta) const {
    const double u = zeta.x * inv_hx + double(half_x), v = zeta.y * inv_hy + double(half_y);
    const double nx = double(2 * half_x), ny = double(2 * half_y);
    if (!(u >= 0 && u <= nx && v >= 0 && v <= ny)) return 0.0;
    const long i = std::min(long(u), std::max(2 * half_x - 1, 0L)), j = std::min(long(v), std::max(2 * half_y - 1, 0L));
    const long stride = 2 * half_x + 1;
    const double tx = half_x > 0 ? u - double(i) : 0.0, ty = half_y > 0 ? v - double(j) : 0.0;
    const double* p = value.data() + j * stride + i;
    const double* q = half_y > 0 ? p + stride : p;
    const long dx = half_x > 0 ? 1 : 0;
    return (1 - ty) * ((1 - tx) * p[0] + tx * p[dx]) + ty * ((1 - tx) * q[0] + tx * q[dx]);
}

namespace {
// A row in the rough-surface limit: the unit-mass Gaussian of covariance c (xx, xy, yy) on a lattice of
// kGaussNodesPerSigma nodes per standard deviation and axis out to kGaussSigmas of them.
SpectrumLobes2d::Row gaussian_row(const std::array<double, 3>& c) {
    SpectrumLobes2d::Row row;
    const double sx = std::sqrt(c[0]), sy = std::sqrt(c[2]), det = c[0] * c[2] - c[1] * c[1];
    row.hx = sx / SpectrumLobes2d::kGaussNodesPerSigma;
    row.hy = sy / SpectrumLobes2d::kGaussNodesPerSigma;
    row.inv_hx = 1.0 / row.hx;
    row.inv_hy = 1.0 / row.hy;
    row.half_x = row.half_y = long(std::ceil(SpectrumLobes2d::kGaussSigmas * SpectrumLobes2d::kGaussNodesPerSigma));
    row.value.assign(std::size_t((2 * row.half_x + 1) * (2 * row.half_y + 1)), 0.0);
    double sum = 0;
    for (long j = -row.half_y; j <= row.half_y; ++j)
        for (long i = -row.half_x; i <= row.half_x; ++i) {
            const double x = double(i) * row.hx, y = double(j) * row.hy;
            const double q = (c[2] * x * x - 2 * c[1] * x * y + c[0] * y * y) / det;
            const double v = std::exp(-0.5 * q);
            row.value[std::size_t((j + row.half_y) * (2 * row.half_x + 1) + (i + row.half_x))] = v;
            sum += v;
        }
    for (double& v : row.value) v /= sum * row.hx * row.hy;
    row.raw_mass = 1.0;
    return row;
}
}  // namespace

SpectrumLobes2d::SpectrumLobes2d(const Psd2d& spectrum, double g_max, bool rough_limit)
    : g_max_(g_max), spectrum_(spectrum) {
    if (!(g_max > 0 && g_max <= 1e7)) fail("2-D measured lobes: g_max must be in (0, 1e7], got {}", g_max);
    // A masked estimate's bins below zero (its scatter where the PSD lies below it: psd_estimate.hpp) would make
    // rho no longer positive definite and the lobes negative: within each ring of width max(dzeta_x, dzeta_y) about
    // zeta = 0 (radial_average's rings, out to the lattice's corners) that holds one, the negative bins are set to 0
    // and the positive ones scaled to keep the ring's sum; a ring whose sum is not positive is set to 0 (the ring
    // route skips it). clipped_fraction() is the negative bins' |sum| over the positive bins' sum.
    {
        const std::size_t hx = spectrum_.half_nx();
        const double dz = std::max(spectrum_.dzeta_x, spectrum_.dzeta_y);
        auto ring = [&](std::size_t kx, std::size_t ky) {
            return std::size_t(std::floor(std::hypot(spectrum_.zeta_x(kx), spectrum_.zeta_y(ky)) / dz + 0.5));
        };
        std::vector<double> sum, negative, positive;
        for (std::size_t ky = 0; ky < spectrum_.ny; ++ky)
            for (std::size_t kx = 0; kx < hx; ++kx) {
                const std::size_t r = ring(kx, ky);
                if (r >= sum.size()) {
                    sum.resize(r + 1, 0.0);
                    negative.resize(r + 1, 0.0);
                    positive.resize(r + 1, 0.0);
                }
                const double v = spectrum_.values[ky * hx + kx] * spectrum_.multiplicity(kx);
                sum[r] += v;
                (v < 0 ? negative[r] : positive[r]) += std::abs(v);
            }
        double all_negative = 0, all_positive = 0;
        for (std::size_t r = 0; r < sum.size(); ++r) {
            all_negative += negative[r];
            all_positive += positive[r];
        }
        clipped_fraction_ = all_positive > 0 ? all_negative / all_positive : 0.0;
        if (all_negative > 0)
            for (std::size_t ky = 0; ky < spectrum_.ny; ++ky)
                for (std::size_t kx = 0; kx < hx; ++kx) {
                    const std::size_t r = ring(kx, ky);
                    if (negative[r] == 0) continue;
                    double& v = spectrum_.values[ky * hx + kx];
                    v = v > 0 && sum[r] > 0 ? v * sum[r] / positive[r] : 0.0;
                }
    }
    const double variance = spectrum_.integral();
    if (!(variance > 0) || !std::isfinite(variance))
        fail("2-D measured lobes: the periodogram's lattice sum is {} (needs > 0)", variance);
    sigma_h_ = std::sqrt(variance);
    for (double& v : spectrum_.values) v /= variance;
    const std::size_t nx = spectrum_.nx, ny = spectrum_.ny, hx = spectrum_.half_nx();
    const double dzx = spectrum_.dzeta_x, dzy = spectrum_.dzeta_y;
    Centred unit;
    centred_plane(nx, ny, dzx, dzy, [&](std::size_t kx, std::size_t ky) { return spectrum_.values[ky * hx + kx]; },
                  unit);

    // The rough-surface limit's moments of the unit periodogram and its switch (rough_limit_g()).
    for (long j = -unit.half_y; j <= unit.half_y; ++j)
        for (long i = -unit.half_x; i <= unit.half_x; ++i) {
            const double x = double(i) * dzx, y = double(j) * dzy, w = unit.at(i, j) * dzx * dzy;
            moment_[0] += w * x * x;
            moment_[1] += w * x * y;
            moment_[2] += w * y * y;
        }
    const double det = moment_[0] * moment_[2] - moment_[1] * moment_[1];
    if (det > 0) {
        for (long j = -unit.half_y; j <= unit.half_y; ++j)
            for (long i = -unit.half_x; i <= unit.half_x; ++i) {
                const double x = double(i) * dzx, y = double(j) * dzy;
                const double q = (moment_[2] * x * x - 2 * moment_[1] * x * y + moment_[0] * y * y) / det;
                kurtosis_ += unit.at(i, j) * dzx * dzy * q * q;
            }
        if (rough_limit && std::isfinite(kurtosis_)) rough_limit_g_ = kurtosis_ / (8.0 * kRoughTolerance);
    }

    // 2. rho on the p-fold lattice.
    const double nyquist = std::min(0.5 * double(nx) * dzx, 0.5 * double(ny) * dzy);
    const std::size_t p_max = std::max<std::size_t>(1, kMaxLattice / std::max(nx, ny));
    padding_ = std::clamp<std::size_t>(std::size_t(std::ceil(kCoverage / nyquist)), 1, p_max);
    const std::size_t fx = padding_ * nx, fy = padding_ * ny, fhx = fx / 2 + 1;
    std::vector<std::complex<double>> padded(fy * fhx, 0.0);
    for (long j = -unit.half_y; j <= unit.half_y; ++j)
        for (long i = 0; i <= unit.half_x; ++i) {
            // Without padding the c2r's own Nyquist column stands for both +- nx/2: it takes both halves.
            const double factor = (padding_ == 1 && nx % 2 == 0 && i == unit.half_x && i > 0) ? 2.0 : 1.0;
            const std::size_t row = std::size_t(((j % long(fy)) + long(fy)) % long(fy));
            padded[row * fhx + std::size_t(i)] += factor * unit.at(i, j) * dzx * dzy;
        }
    std::vector<double> rho(fx * fy);
    {
        fftw_plan raw;
        {
            std::lock_guard lock(heightmap::fftw_planner_mutex());
            raw = fftw_plan_dft_c2r_2d(int(fy), int(fx), reinterpret_cast<fftw_complex*>(padded.data()), rho.data(),
                                       FFTW_ESTIMATE);
        }
        PlanGuard plan(raw);
        fftw_execute(plan.plan);
    }
    const double dxf = kTwoPi / (double(fx) * dzx), dyf = kTwoPi / (double(fy) * dzy);
    auto rho_at = [&](long i, long j) {
        return rho[std::size_t(((j % long(fy)) + long(fy)) % long(fy)) * fx + std::size_t(((i % long(fx)) + long(fx)) % long(fx))];
    };
    // The extremes of rho beyond each Chebyshev radius, for the windows of step 3.
    const long rings = long(std::max(fx, fy) / 2) + 1;
    std::vector<double> beyond_max(std::size_t(rings) + 1, -HUGE_VAL), beyond_min(std::size_t(rings) + 1, HUGE_VAL);
    for (long j = -long(fy / 2); j < long(fy - fy / 2); ++j)
        for (long i = -long(fx / 2); i < long(fx - fx / 2); ++i) {
            const std::size_t r = std::size_t(ring_of(i, j));
            beyond_max[r] = std::max(beyond_max[r], rho_at(i, j));
            beyond_min[r] = std::min(beyond_min[r], rho_at(i, j));
        }
    for (long r = rings - 1; r >= 0; --r) {
        beyond_max[std::size_t(r)] = std::max(beyond_max[std::size_t(r)], beyond_max[std::size_t(r) + 1]);
        beyond_min[std::size_t(r)] = std::min(beyond_min[std::size_t(r)], beyond_min[std::size_t(r) + 1]);
    }

    // 3. Rows, with a progress bar on stderr for a build of more than about a second (~1e8 lattice points
    // transformed: measured 0.6-1 s on this project's VM, docs/PERFORMANCE.md).
    const int last = int(std::ceil(std::log10(g_max / kMinG) * kRowsPerDecade - 1e-9));
    const double work = double(fx) * double(fy) * double(std::max(last, 3) + 2);
    Progress progress(fmt::format("2-D measured lobes ({} x {} lattice, {} rows)", fx, fy, std::max(last, 3) + 2),
                      std::uint64_t(std::max(last, 3) + 2), work > 1e8);
    double edge = 0;
    std::vector<double> f;                     // one row's window of e^{-g (1 - rho)} - e^{-g}
    std::vector<std::complex<double>> out;     // its transform
    Centred lobe;                              // on the full plane
    rows_.push_back(make_row(unit, 1.0, edge));  // on the map's own lattice: its edge is the band's, nothing folds
    row_g_.push_back(0.0);
    progress.advance();
    for (int n = 0; n <= std::max(last, 3); ++n) {  // at least the 4 rows of one cubic stencil
        const double g = kMinG * std::pow(10.0, double(n) / kRowsPerDecade);
        if (g >= rough_limit_g_) {
            rows_.push_back(gaussian_row({g * moment_[0], g * moment_[1], g * moment_[2]}));
            row_g_.push_back(g);
            ++rough_rows_;
            progress.advance();
            continue;
        }
        const double e = std::exp(-g), f0 = -std::expm1(-g);
        // The window: the smallest Chebyshev radius beyond which |f| < kCropValue f(0).
        long w = 1;
        auto beyond = [&](long r) {
            const double hi = beyond_max[std::size_t(r)], lo = beyond_min[std::size_t(r)];
            return std::max(std::exp(-g * (1.0 - hi)) - e, e * -std::expm1(g * lo));
        };
        while (w < rings && beyond(w) >= kCropValue * f0) ++w;
        const std::size_t wx = std::min(fx, power_of_two_at_least(std::size_t(2 * w))),
                          wy = std::min(fy, power_of_two_at_least(std::size_t(2 * w)));
        f.resize(wx * wy);  // every element written below
        out.resize(wy * (wx / 2 + 1));
        // The window's node (i, j), i in [-wx/2, wx - wx/2), sits at f[wrap(j, wy) * wx + wrap(i, wx)] and reads
        // rho[wrap(j, fy) * fx + wrap(i, fx)]: per row two contiguous runs (i >= 0, i < 0).
        const std::size_t right = wx - wx / 2;
        for (std::size_t y = 0; y < wy; ++y) {
            const std::size_t ry = y < wy - wy / 2 ? y : y + fy - wy;
            const double* r = rho.data() + ry * fx;
            double* out_row = f.data() + y * wx;
            for (std::size_t x = 0; x < right; ++x) out_row[x] = math::fast_exp(g * (r[x] - 1.0)) - e;
            const double* r_left = r + (fx - wx);
            for (std::size_t x = right; x < wx; ++x) out_row[x] = math::fast_exp(g * (r_left[x] - 1.0)) - e;
        }
        {
            fftw_plan raw;
            {
                std::lock_guard lock(heightmap::fftw_planner_mutex());
                raw = fftw_plan_dft_r2c_2d(int(wy), int(wx), f.data(), reinterpret_cast<fftw_complex*>(out.data()),
                                           FFTW_ESTIMATE);
            }
            PlanGuard plan(raw);
            fftw_execute(plan.plan);
        }
        const double scale = dxf * dyf / (4.0 * kPi * kPi);
        const std::size_t ohx = wx / 2 + 1;
        centred_plane(wx, wy, kTwoPi / (double(wx) * dxf), kTwoPi / (double(wy) * dyf),
                      [&](std::size_t kx, std::size_t ky) { return scale * out[ky * ohx + kx].real(); }, lobe);
        rows_.push_back(make_row(lobe, f0, edge));
        row_g_.push_back(g);
        edge_fraction_ = std::max(edge_fraction_, edge);
        progress.advance();
    }
    progress.finish();
    for (std::size_t first = 0; first + 5 <= rows_.size(); ++first) {
        const Row& a = rows_[first + 1];
        bool shared = a.half_x > 0 && a.half_y > 0;
        for (std::size_t n = 2; n <= 4; ++n) {
            const Row& b = rows_[first + n];
            shared = shared && b.half_x == a.half_x && b.half_y == a.half_y && b.hx == a.hx && b.hy == a.hy;
        }
        shared_lattice_.push_back(shared);
    }
    cdfs_.resize(rows_.size());
    cdf_once_ = std::make_unique<std::once_flag[]>(rows_.size());
    std::uint64_t h = fnv1a(spectrum_.values.data(), spectrum_.values.size() * sizeof(double));
    const double dims[4] = {double(nx), double(ny), dzx, dzy};
    h = fnv1a(dims, sizeof dims, h);
    key_ = fmt::format("spectrum-lobes-2d:v{}:{:016x}:{}x{}:sigma_h={:.17g}:window={}:p={}:rows/decade={}:cells={}"
                       ":rough-limit={:.17g}/{}/{}",
                       kVersion, h, nx, ny, sigma_h_, int(spectrum_.window), padding_, kRowsPerDecade, kMaxCells,
                       rough_limit_g_, kGaussNodesPerSigma, kGaussSigmas);
}

SpectrumLobes2d::Mixture SpectrumLobes2d::mixture(double g, bool first_order_only) const {
    if (first_order_only || g <= 0) return {0, 0, 1.0, 0.0};
    if (g < kMinG) {
        const double t = g / kMinG;
        return {0, 1, 1.0 - t, t};
    }
    const double t = std::log(g / kMinG) / std::log(10.0) * kRowsPerDecade;
    const std::size_t last = rows_.size() - 1;
    const std::size_t a = std::min(last, std::size_t(1 + std::size_t(t)));
    if (a == last) return {a, a, 1.0, 0.0};
    const double w = t - double(a - 1);
    return {a, a + 1, 1.0 - w, w};
}

// Cubic Lagrange in ln g over the 4 rows around it (one-sided at the ends).
inline SpectrumLobes2d::Cubic SpectrumLobes2d::cubic(double log_g) const {
    const double t = (log_g - std::log(kMinG)) * (kRowsPerDecade / std::numbers::ln10);
    const long nodes = long(rows_.size()) - 1;  // rows 1 .. nodes at t = 0 .. nodes - 1
    const long first = std::clamp(long(t) - 1, 0L, nodes - 4);
    return {first, math::lagrange4_weights(t - double(first))};
}

double SpectrumLobes2d::shape(double g, Vec2 zeta) const { return shape(g, math::fast_log(g), zeta); }

double SpectrumLobes2d::shape(double g, double log_g, Vec2 zeta) const {
    if (!(g >= 0 && g <= g_max_)) fail("2-D measured lobe: g = {} outside [0, {}]", g, g_max_);
    if (g < kMinG) {
        const Mixture m = mixture(g, false);
        return m.wa * rows_[m.a].at(zeta) + m.wb * rows_[m.b].at(zeta);
    }
    const auto [first, w] = cubic(log_g);
    const Row* stencil = rows_.data() + first + 1;
    double sum = 0;
    if (shared_lattice_[std::size_t(first)]) {
        // One lattice (the common case: the rows of a map's lattice before their windows shrink): its cell and
        // bilinear weights once, then the four rows' corners combined with the cubic's weights.
        const Row& r = stencil[0];
        const double x = zeta.x * r.inv_hx + double(r.half_x), y = zeta.y * r.inv_hy + double(r.half_y);
        if (!(x >= 0 && x <= double(2 * r.half_x) && y >= 0 && y <= double(2 * r.half_y))) return 0.0;
        const long i = std::min(long(x), 2 * r.half_x - 1), j = std::min(long(y), 2 * r.half_y - 1);
        const long stride = 2 * r.half_x + 1, at = j * stride + i;
        const double tx = x - double(i), ty = y - double(j);
        double c00 = 0, c10 = 0, c01 = 0, c11 = 0;
        for (int n = 0; n < 4; ++n) {
            const double* p = stencil[n].value.data() + at;
            c00 += w[n] * p[0];
            c10 += w[n] * p[1];
            c01 += w[n] * p[stride];
            c11 += w[n] * p[stride + 1];
        }
        sum = (1 - ty) * (c00 + tx * (c10 - c00)) + ty * (c01 + tx * (c11 - c01));
    } else {
        for (int n = 0; n < 4; ++n) sum += w[n] * stencil[n].at(zeta);
    }
    return std::max(sum, 0.0);  // the cubic's undershoot where a row is 0 and its neighbours are not
}

double SpectrumLobes2d::eval(double g, Vec2 zeta) const { return eval(g, math::fast_log(g), zeta); }

double SpectrumLobes2d::eval(double g, double log_g, Vec2 zeta) const {
    return g > 0 ? math::one_minus_exp(g) * shape(g, log_g, zeta) : 0.0;
}

double SpectrumLobes2d::first_order(Vec2 zeta) const { return rows_[0].at(zeta); }

namespace {
// One axis of Bins: node values v[-nodes .. nodes] at spacing s onto cells -half .. half of spacing h, at stride
// `stride` in out (added to): summed when s < h, the linear interpolant at the cell centres (0 beyond the outermost
// nodes, as Row::at) times h otherwise.
void bin_axis(const double* v, long nodes, double s, double h, long half, double* out, std::size_t stride) {
    if (s < h) {
        for (long i = -nodes; i <= nodes; ++i) {
            const long c = std::lround(double(i) * s / h);
            if (c >= -half && c <= half) out[std::size_t(c + half) * stride] += s * v[i + nodes];
        }
        return;
    }
    for (long c = -half; c <= half; ++c) {
        const double u = double(c) * h / s + double(nodes);
        if (!(u >= 0 && u <= double(2 * nodes))) continue;
        const long i = std::min(long(u), std::max(2 * nodes - 1, 0L));
        const double t = nodes > 0 ? u - double(i) : 0.0;
        out[std::size_t(c + half) * stride] += h * ((1 - t) * v[i] + (nodes > 0 ? t * v[i + 1] : 0.0));
    }
}
}  // namespace

SpectrumLobes2d::Bins SpectrumLobes2d::bins(double h, double extent, double g_hi) const {
    if (!(h > 0 && extent > 0 && std::isfinite(extent / h)))
        fail("2-D measured lobes: bins of spacing {} out to {} rad/um", h, extent);
    Bins b;
    b.h = h;
    b.half = long(std::ceil(extent / h));
    const long n = 2 * b.half + 1;
    // The last row any g <= g_hi reads: the cubic's stencil at g_hi (rows 0 and 1 below kMinG).
    const double top = std::min(g_hi, g_max_);
    const std::size_t last = top < kMinG ? 1 : std::size_t(cubic(std::log(top)).first + 4);
    b.mass.resize(rows_.size());
    for (std::size_t r = 0; r <= std::min(last, rows_.size() - 1); ++r) {
        const Row& row = rows_[r];
        const long nx = 2 * row.half_x + 1, ny = 2 * row.half_y + 1;
        std::vector<double> along_x(std::size_t(ny * n), 0.0);  // [node row j][cell i]
        for (long j = 0; j < ny; ++j)
            bin_axis(row.value.data() + j * nx, row.half_x, row.hx, h, b.half, along_x.data() + j * n, 1);
        std::vector<double> m(std::size_t(n * n), 0.0);
        std::vector<double> column(std::size_t(ny), 0.0);
        for (long i = 0; i < n; ++i) {
            for (long j = 0; j < ny; ++j) column[std::size_t(j)] = along_x[std::size_t(j * n + i)];
            bin_axis(column.data(), row.half_y, row.hy, h, b.half, m.data() + i, std::size_t(n));
        }
        b.mass[r] = std::move(m);
    }
    return b;
}

double SpectrumLobes2d::binned_shape(const Bins& bins, std::size_t index, double g, bool first_order_only) const {
    if (first_order_only || g <= 0) return bins.mass[0][index];
    if (g < kMinG) {
        const Mixture m = mixture(g, false);
        return m.wa * bins.mass[m.a][index] + m.wb * bins.mass[m.b][index];
    }
    const auto [first, w] = cubic(math::fast_log(g));
    double sum = 0;
    for (int n = 0; n < 4; ++n) sum += w[std::size_t(n)] * bins.mass[std::size_t(first + 1 + n)][index];
    return std::max(sum, 0.0);
}

double SpectrumLobes2d::finest_spacing(double g_lo, double g_hi) const {
    double h = HUGE_VAL;
    for (std::size_t r = 0; r < rows_.size(); ++r) {
        // Row r serves g between its neighbours' nodes.
        const double below = r > 0 ? row_g_[r - 1] : 0.0, above = r + 1 < rows_.size() ? row_g_[r + 1] : HUGE_VAL;
        if (above >= g_lo && below <= g_hi) h = std::min({h, rows_[r].hx, rows_[r].hy});
    }
    return h;
}

// The bilinear cells between nodes (i, j) .. (i + 1, j + 1), cell index j * 2 half_x + i (i, j from 0): cumulative
// masses (the mean of the corners; the node spacing's area is a common factor).
const std::vector<double>& SpectrumLobes2d::cdf(std::size_t row) const {
    std::call_once(cdf_once_[row], [&] {
        const Row& r = rows_[row];
        const long cx = std::max(2 * r.half_x, 1L), cy = std::max(2 * r.half_y, 1L), stride = 2 * r.half_x + 1;
        std::vector<double> c(std::size_t(cx * cy));
        double sum = 0;
        for (long j = 0; j < cy; ++j)
            for (long i = 0; i < cx; ++i) {
                const double* p = r.value.data() + j * stride + i;
                const long dx = r.half_x > 0 ? 1 : 0, dy = r.half_y > 0 ? stride : 0;
                sum += 0.25 * (p[0] + p[dx] + p[dy] + p[dx + dy]);
                c[std::size_t(j * cx + i)] = sum;
            }
        cdfs_[row] = std::move(c);
    });
    return cdfs_[row];
}

namespace {
// x in [0, 1] with density proportional to a (1 - x) + b x (a, b >= 0, a + b > 0) at CDF value u, in the form without
// cancellation.
double linear_inverse(double a, double b, double u) {
    const double root = std::sqrt(std::max(0.0, a * a + u * (b * b - a * a)));
    return a + root > 0 ? std::clamp(u * (a + b) / (a + root), 0.0, 1.0) : u;
}
}  // namespace

Vec2 SpectrumLobes2d::sample(double g, bool first_order_only, double u_row, Vec2 u) const {
    const Mixture m = mixture(g, first_order_only);
    std::size_t row = m.a;
    double v = m.wb > 0 ? u_row / m.wa : u_row;
    if (m.wb > 0 && u_row >= m.wa) {
        row = m.b;
        v = (u_row - m.wa) / m.wb;
    }
    const std::vector<double>& c = cdf(row);
    const double target = std::min(v, 1.0) * c.back();
    const std::size_t cell = std::min(std::size_t(std::upper_bound(c.begin(), c.end(), target) - c.begin()), c.size() - 1);
    const Row& r = rows_[row];
    const long cx = std::max(2 * r.half_x, 1L), stride = 2 * r.half_x + 1;
    const long i = long(cell) % cx, j = long(cell) / cx;
    const double* p = r.value.data() + j * stride + i;
    const long dx = r.half_x > 0 ? 1 : 0, dy = r.half_y > 0 ? stride : 0;
    // Within the cell the bilinear density: x from its marginal, y given x.
    const double x = linear_inverse(p[0] + p[dy], p[dx] + p[dx + dy], u.x);
    const double y = linear_inverse(p[0] * (1 - x) + p[dx] * x, p[dy] * (1 - x) + p[dx + dy] * x, u.y);
    return {(double(i - r.half_x) + x) * r.hx, (double(j - r.half_y) + y) * r.hy};
}

double SpectrumLobes2d::sample_density(double g, bool first_order_only, Vec2 zeta) const {
    const Mixture m = mixture(g, first_order_only);
    auto row_density = [&](std::size_t row) {
        const Row& r = rows_[row];
        return r.at(zeta) / (cdf(row).back() * r.hx * r.hy);
    };
    return m.wa * row_density(m.a) + (m.wb > 0 ? m.wb * row_density(m.b) : 0.0);
}

}  // namespace surfscatter::surface
