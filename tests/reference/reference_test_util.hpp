#pragma once
// Profiles and integrals shared by the reference tests.
#include <cmath>
#include <complex>
#include <functional>
#include <random>
#include <vector>

#include "surfscatter/math/vec.hpp"
#include "surfscatter/reference/exact_1d.hpp"

namespace reference_test {

namespace sr = surfscatter::reference;

// Solver options for a test.
inline sr::Exact1dOptions solver_options(double lambda_nm, double theta_deg, sr::Polarisation pol, double g,
                                         double ppw = 10) {
    sr::Exact1dOptions o;
    o.lambda_nm = lambda_nm;
    o.theta_i_rad = theta_deg * surfscatter::kDegree;
    o.polarisation = pol;
    o.beam_width_um = g;
    o.points_per_wavelength = ppw;
    return o;
}

// The relative L1 distance of two patterns.
inline double pattern_distance(const sr::FarField& a, const sr::FarField& b) {
    const auto ia = a.intensity_per_rad(), ib = b.intensity_per_rad();
    double diff = 0, norm = 0;
    for (std::size_t j = 0; j < ia.size(); ++j) {
        diff += std::abs(ia[j] - ib[j]);
        norm += ib[j];
    }
    return diff / norm;
}

// Samples of f on [-half_length, half_length] with the given step.
inline sr::Profile sample_profile(const std::function<double(double)>& f, double half_length, double step) {
    sr::Profile p;
    const auto n = static_cast<std::size_t>(std::lround(2.0 * half_length / step)) + 1;
    p.x0_um = -half_length;
    p.spacing_um = 2.0 * half_length / static_cast<double>(n - 1);
    for (std::size_t j = 0; j < n; ++j) p.h_um.push_back(f(p.x0_um + p.spacing_um * static_cast<double>(j)));
    return p;
}

// A smooth random profile: a sum of `terms` cosines with wavelengths uniformly in [min_period, max_period] um,
// random phases and equal amplitudes scaled to the rms height sigma.
inline std::function<double(double)> random_cosines(double sigma, double min_period, double max_period, int terms,
                                                    unsigned seed) {
    std::mt19937 engine(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<double> k, phase;
    for (int t = 0; t < terms; ++t) {
        k.push_back(surfscatter::kTwoPi / (min_period + (max_period - min_period) * u(engine)));
        phase.push_back(surfscatter::kTwoPi * u(engine));
    }
    const double amplitude = sigma * std::sqrt(2.0 / terms);
    return [=](double x) {
        double h = 0;
        for (std::size_t t = 0; t < k.size(); ++t) h += amplitude * std::cos(k[t] * x + phase[t]);
        return h;
    };
}

// Trapezoid integral of intensity_per_rad over theta_o (the grid is uniform).
inline double total_power(const sr::FarField& f) {
    const auto intensity = f.intensity_per_rad();
    const double step = f.theta_o_rad[1] - f.theta_o_rad[0];
    double sum = 0;
    for (std::size_t j = 0; j < intensity.size(); ++j)
        sum += intensity[j] * ((j == 0 || j + 1 == intensity.size()) ? 0.5 : 1.0);
    return sum * step;
}

// Power within |theta_o - theta| <= half_width (radians).
inline double power_near(const sr::FarField& f, double theta, double half_width) {
    const auto intensity = f.intensity_per_rad();
    const double step = f.theta_o_rad[1] - f.theta_o_rad[0];
    double sum = 0;
    for (std::size_t j = 0; j < intensity.size(); ++j)
        if (std::abs(f.theta_o_rad[j] - theta) <= half_width) sum += intensity[j];
    return sum * step;
}

// The field a flat perfect conductor reflects, from the incident beam's values on z = 0 by its plane-wave spectrum
// A(K) = int psi_inc(x, 0) e^{-iKx} dx (direct trapezoid quadrature, spectrally accurate for the Gaussian taper):
// per radian k cos^2(theta) |A(k sin theta)|^2 / (2 pi P_inc), for s exactly and for p to O((k g)^-4).
inline double mirror_intensity(double k, double theta_i, double g, double theta_o) {
    const double step = 0.25 / k, half = 6.0 * g;  // 25 points a wavelength; the taper is exp(-36) at the ends
    std::complex<double> a = 0;
    for (double x = -half; x <= half; x += step)
        a += sr::thorsos_beam(k, theta_i, g, x, 0.0) * std::exp(std::complex<double>(0, -k * std::sin(theta_o) * x));
    a *= step;
    return k * std::pow(std::cos(theta_o), 2) * std::norm(a) / (surfscatter::kTwoPi * sr::incident_power(k, theta_i, g));
}

}  // namespace reference_test
