#include "surfscatter/bsdf/incidence_tables.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include "surfscatter/bsdf/rayleigh_rice.hpp"
#include "surfscatter/core/error.hpp"

namespace surfscatter::bsdf {

namespace {

constexpr double kMinCosine = 1e-6;

// Cubic through (x[0], y[0]) .. (x[3], y[3]) as coefficients of d = x - a over [a, b] (a < b inside the nodes): from
// its values at t = (x - a) / (b - a) = 0, 1/3, 2/3, 1 (Lagrange), the monomial form in t, then c_n / (b - a)^n.
std::array<double, 4> interval_cubic(const double* x, const double* y, double a, double b) {
    std::array<double, 4> v{};
    for (int m = 0; m < 4; ++m) {
        const double at = a + (b - a) * m / 3.0;
        for (int i = 0; i < 4; ++i) {
            double w = y[i];
            for (int j = 0; j < 4; ++j)
                if (j != i) w *= (at - x[j]) / (x[i] - x[j]);
            v[m] += w;
        }
    }
    // p(t) = c0 + c1 t + c2 t^2 + c3 t^3 through v at t = 0, 1/3, 2/3, 1.
    const double h = b - a;
    return {v[0], (-11.0 * v[0] + 18.0 * v[1] - 9.0 * v[2] + 2.0 * v[3]) / (2.0 * h),
            (18.0 * v[0] - 45.0 * v[1] + 36.0 * v[2] - 9.0 * v[3]) / (2.0 * h * h),
            (-9.0 * v[0] + 27.0 * v[1] - 27.0 * v[2] + 9.0 * v[3]) / (2.0 * h * h * h)};
}

}  // namespace

NodeAxis ghs_incidence_axis() {
    std::vector<double> cosines;
    for (int j = kGhsThetaNodes - 1; j >= 0; --j) {
        const double u = double(j) / (kGhsThetaNodes - 1);
        const double theta = 90.0 * kDegree * (1.0 - (1.0 - u) * (1.0 - u) * (1.0 - u));
        cosines.push_back(j == 0 ? 1.0 : std::max(kMinCosine, std::cos(theta)));
    }
    NodeAxis axis(cosines);
    if (axis.size() != kGhsThetaNodes) fail("internal: {} incidence nodes, expected {}", axis.size(), kGhsThetaNodes);
    return axis;
}

NodeAxis ghs_wavelength_axis() {
    std::vector<double> lambdas{kGhsMinWavelength};
    while (lambdas.back() < kGhsMaxWavelength) lambdas.push_back(lambdas.back() * std::exp(0.02));
    return NodeAxis(lambdas);
}

void ghs_wavelength_out_of_range(double lambda_nm) {
    fail("wavelength {} nm outside [{}, {}] nm", lambda_nm, kGhsMinWavelength, kGhsMaxWavelength);
}

IncidenceTable fit_incidence_table(const std::array<double, kGhsThetaNodes>& x,
                                   const std::array<double, kGhsThetaNodes>& first,
                                   const std::array<double, kGhsThetaNodes>& second) {
    IncidenceTable t;
    for (int j = 0; j + 1 < kGhsThetaNodes; ++j) {
        const int from = std::clamp(j - 1, 0, kGhsThetaNodes - 4);  // the 4 nodes around the interval
        const auto a = interval_cubic(&x[from], &first[from], x[j], x[j + 1]);
        const auto b = interval_cubic(&x[from], &second[from], x[j], x[j + 1]);
        for (int p = 0; p < 4; ++p) t[j].c[p][0] = a[p], t[j].c[p][1] = b[p];
    }
    return t;
}

double outgoing_fresnel(const material::Conductor& material, FresnelMode mode, const Vec3& wi, const Vec3& wo,
                        double lambda_nm) {
    switch (mode) {
        case FresnelMode::incident: return material.reflectance(std::min(1.0, wi.z), lambda_nm);
        case FresnelMode::half: {
            const Vec3 h = normalize(wi + wo);
            return material.reflectance(std::clamp(dot(wi, h), 0.0, 1.0), lambda_nm);
        }
        case FresnelMode::rr: {
            if (material.is_perfect()) return rayleigh_rice_q_perfect(wi, wo);
            const std::complex<double> n = material.ior(lambda_nm);
            return rayleigh_rice_q(wi, wo, n * n);
        }
    }
    return 0.0;
}

}  // namespace surfscatter::bsdf
