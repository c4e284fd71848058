#pragma once
// A banded complex matrix (entries with |i - j| <= band) and its LU factors with partial pivoting by LAPACK's
// zgbtrf / zgbtrs (O(N band^2) to factor, O(N band) per solve): the near-field preconditioner of the exact 1-D
// solver's iterative route for a perfect conductor in p (docs/REFERENCE.md, "Solve").
#include <complex>
#include <cstddef>
#include <string_view>
#include <vector>

#include <Eigen/Dense>

namespace surfscatter::reference {

// sum_q a[q] x[q] over `count` entries in real arithmetic with two independent pairs of sums (the band products'
// inner loop: one pair is a chain of dependent additions, ~4x slower; libgcc's complex multiply checks every product
// for NaN).
inline std::complex<double> dot_segment(const std::complex<double>* a, const std::complex<double>* x, std::size_t count) {
    const auto* __restrict ad = reinterpret_cast<const double*>(a);
    const auto* __restrict xd = reinterpret_cast<const double*>(x);
    double re0 = 0.0, im0 = 0.0, re1 = 0.0, im1 = 0.0;
    std::size_t q = 0;
    for (; q + 1 < count; q += 2) {
        re0 += ad[2 * q] * xd[2 * q] - ad[2 * q + 1] * xd[2 * q + 1];
        im0 += ad[2 * q] * xd[2 * q + 1] + ad[2 * q + 1] * xd[2 * q];
        re1 += ad[2 * q + 2] * xd[2 * q + 2] - ad[2 * q + 3] * xd[2 * q + 3];
        im1 += ad[2 * q + 2] * xd[2 * q + 3] + ad[2 * q + 3] * xd[2 * q + 2];
    }
    if (q < count) {
        re0 += ad[2 * q] * xd[2 * q] - ad[2 * q + 1] * xd[2 * q + 1];
        im0 += ad[2 * q] * xd[2 * q + 1] + ad[2 * q + 1] * xd[2 * q];
    }
    return {re0 + re1, im0 + im1};
}

struct BandedMatrix {
    std::size_t n = 0, band = 0;
    std::vector<std::complex<double>> data;  // row i holds columns i - band .. i + band
    BandedMatrix() = default;
    BandedMatrix(std::size_t size, std::size_t half_width);
    std::complex<double>& at(std::size_t i, std::size_t j) { return data[i * (2 * band + 1) + j + band - i]; }
    const std::complex<double>& at(std::size_t i, std::size_t j) const { return data[i * (2 * band + 1) + j + band - i]; }
    Eigen::VectorXcd multiply(const Eigen::VectorXcd& v) const;
    // The same matrix with the entries beyond |i - j| <= half_width dropped.
    BandedMatrix truncated(std::size_t half_width) const;
};

class BandedLu {
public:
    // Throws Error naming `what` when a pivot is exactly zero.
    BandedLu(const BandedMatrix& a, std::string_view what);
    Eigen::VectorXcd solve(Eigen::VectorXcd b) const;

private:
    int n_ = 0, band_ = 0, ldab_ = 0;
    std::vector<std::complex<double>> factors_;
    std::vector<int> pivots_;
};

}  // namespace surfscatter::reference
