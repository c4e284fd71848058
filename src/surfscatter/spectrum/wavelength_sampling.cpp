#include "surfscatter/spectrum/wavelength_sampling.hpp"

#include <algorithm>
#include <cmath>

namespace surfscatter::spectrum {

namespace {
// sech^2 density: p(lambda) = a sech^2(a (lambda - c)) / (T1 - T0) with T = tanh(a (lambda_bound - c)); its CDF is
// (tanh(a (lambda - c)) - T0) / (T1 - T0), inverted in closed form for the cell edges.
constexpr double kA = 0.0072;   // 1/nm
constexpr double kC = 538.0;    // nm
const double kT0 = std::tanh(kA * (kSampledLambdaMin - kC));
const double kT1 = std::tanh(kA * (kSampledLambdaMax - kC));

double sech2_inverse_cdf(double u) {
    const double t = kT0 + u * (kT1 - kT0);
    return std::clamp(kC + std::atanh(t) / kA, kSampledLambdaMin, kSampledLambdaMax);
}

// Cell k covers u in [k, k + 1) / kVisibleCells and lambda in [lambda0, lambda0 + width).
struct Cell {
    double lambda0, width, pdf;
};

struct Cells {
    std::array<Cell, kVisibleCells> cell{};
    Cells() {
        double lo = kSampledLambdaMin;
        for (int k = 0; k < kVisibleCells; ++k) {
            const double hi = k + 1 == kVisibleCells ? kSampledLambdaMax
                                                     : sech2_inverse_cdf(static_cast<double>(k + 1) / kVisibleCells);
            cell[static_cast<std::size_t>(k)] = {lo, hi - lo, 1.0 / (kVisibleCells * (hi - lo))};
            lo = hi;
        }
    }
};
const Cells kCells;

const Cell& cell_at(double u, double& fraction) {
    const double s = std::clamp(u, 0.0, 1.0) * kVisibleCells;
    const int k = std::min(static_cast<int>(s), kVisibleCells - 1);
    fraction = s - k;
    return kCells.cell[static_cast<std::size_t>(k)];
}

}  // namespace

double visible_wavelength_sech2_pdf(double lambda_nm) {
    if (!(lambda_nm >= kSampledLambdaMin && lambda_nm <= kSampledLambdaMax)) return 0.0;
    const double t = std::tanh(kA * (lambda_nm - kC));
    return kA * (1.0 - t) * (1.0 + t) / (kT1 - kT0);
}

double visible_wavelength_pdf(double lambda_nm) {
    if (!(lambda_nm >= kSampledLambdaMin && lambda_nm <= kSampledLambdaMax)) return 0.0;
    // The cell from the sech^2 CDF, then corrected by the edges the table holds (they are the same up to rounding).
    const double u = (std::tanh(kA * (lambda_nm - kC)) - kT0) / (kT1 - kT0);
    int k = std::clamp(static_cast<int>(u * kVisibleCells), 0, kVisibleCells - 1);
    while (k > 0 && lambda_nm < kCells.cell[static_cast<std::size_t>(k)].lambda0) --k;
    while (k + 1 < kVisibleCells && lambda_nm >= kCells.cell[static_cast<std::size_t>(k + 1)].lambda0) ++k;
    return kCells.cell[static_cast<std::size_t>(k)].pdf;
}

double sample_visible_wavelength(double u) {
    double fraction = 0;
    const Cell& c = cell_at(u, fraction);
    return c.lambda0 + fraction * c.width;
}

SampledWavelengths SampledWavelengths::sample_visible(double u) {
    SampledWavelengths w;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        double ui = u + static_cast<double>(i) / kSpectrumSamples;
        if (ui >= 1.0) ui -= 1.0;
        double fraction = 0;
        const Cell& c = cell_at(ui, fraction);
        w.lambda[static_cast<std::size_t>(i)] = c.lambda0 + fraction * c.width;
        w.pdf[static_cast<std::size_t>(i)] = c.pdf;
    }
    return w;
}

SampledWavelengths SampledWavelengths::sample_uniform(double u) {
    SampledWavelengths w;
    const double range = kSampledLambdaMax - kSampledLambdaMin;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        double ui = u + static_cast<double>(i) / kSpectrumSamples;
        if (ui >= 1.0) ui -= 1.0;
        w.lambda[static_cast<std::size_t>(i)] = kSampledLambdaMin + ui * range;
        w.pdf[static_cast<std::size_t>(i)] = 1.0 / range;
    }
    return w;
}

}  // namespace surfscatter::spectrum
