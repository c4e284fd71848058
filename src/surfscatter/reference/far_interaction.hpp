#pragma once
// The outside kernels between nodes more than `near` apart, applied in O(N log N) (docs/REFERENCE.md, "Solve"): with
// dx = x_j - x_i and dz = h_j - h_i, Graf's multiplication theorem expands about the flat line,
//   H0(k R) = sum_m (1/m!) (-k dz^2 / (2|dx|))^m H_m(k|dx|),  H1(k R)/R = sum_m (1/m!) (-k dz^2/(2|dx|))^m H_{m+1}(k|dx|)/|dx|,
// convergent for |dz| < |dx|; each term is a Toeplitz kernel in dx times powers of h_i and h_j (binomial expansion of
// dz^p), applied by FFT convolution (the canonical grid of Tsang's BMIA/CAG, here with as many terms as the
// tolerance needs). The terms are counted for the profile's height range: the tail is below `tolerance` times the
// series' first term at every far separation.
#include <cstddef>
#include <vector>

#include <Eigen/Dense>

#include "surfscatter/reference/circulant.hpp"

namespace surfscatter::reference {

class FarInteraction {
public:
    // Nodes x_j = j step (the origin does not matter), heights h and slopes dh (um); pairs with |i - j| > near.
    // Throws Error when the series does not converge within kMaxTerms terms (near too small for the height range).
    FarInteraction(double step_um, const std::vector<double>& h, const std::vector<double>& dh, double k_per_um,
                   std::size_t near, double tolerance);
    ~FarInteraction();
    FarInteraction(const FarInteraction&) = delete;
    FarInteraction& operator=(const FarInteraction&) = delete;

    // sum over far j of step (i/4) H0(k R_ij) v_j: the single layer's far part.
    Eigen::VectorXcd single(const Eigen::VectorXcd& v) const;
    // sum over far j of step (-ik/4) H1(k R_ij)/R_ij (dz - h'_j dx) v_j: the double layer's far part.
    Eigen::VectorXcd double_layer(const Eigen::VectorXcd& v) const;

    // single(single_density) - double_layer(double_density) with one set of inverse FFTs (a metal's product).
    Eigen::VectorXcd single_minus_double_layer(const Eigen::VectorXcd& single_density,
                                               const Eigen::VectorXcd& double_density) const;

    int terms() const { return terms_; }  // m = 0 .. terms - 1

    // The number of terms the far pairs of a profile with this height range need (0 when kMaxTerms do not suffice).
    static int terms_needed(double step_um, std::size_t nodes, double height_range_um, double k_per_um,
                            std::size_t near, double tolerance);
    static constexpr int kMaxTerms = 40;
    // Bytes an instance with this many terms holds for `nodes` nodes after its first product: the kernel spectra,
    // the product workspace, the heights and slopes, and the constructor's and apply's temporaries.
    static double bytes(std::size_t nodes, int terms);

private:
    static constexpr std::size_t kBlock = 256;  // frequencies per cache block of the spectral products
    // single(*single_density) - double_layer(*double_density); a null density is left out.
    Eigen::VectorXcd apply(const Eigen::VectorXcd* double_density, const Eigen::VectorXcd* single_density) const;
    std::size_t n_ = 0, size_ = 0;  // nodes, FFT length (>= 2 n)
    int terms_ = 0;
    std::vector<double> h_, dh_;  // heights centred on their mid-range
    // Kernel spectra: single_[m], odd_[m] (f_m for dz^(2m+1)) and slope_[m] (-f_m dx for h'_j dz^(2m)).
    std::vector<Eigen::VectorXcd> single_, odd_, slope_;
    FftPlans plans_;
    // Workspace of apply, kept between products (a solve applies the operators tens of times).
    mutable std::vector<Eigen::VectorXcd> density_, out_spectra_;
    mutable Eigen::VectorXcd padded_;
};

}  // namespace surfscatter::reference
