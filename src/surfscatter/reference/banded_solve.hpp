#pragma once
// A banded complex matrix (entries with |i - j| <= band) and its LU factors with partial pivoting by LAPACK's
// zgbtrf / zgbtrs (O(N band^2) to factor, O(N band) per solve): the near-field preconditioner of the exact 1-D
// solver's iterative route (docs/REFERENCE.md, "Solve").
#include <complex>
#include <cstddef>
#include <string_view>
#include <vector>

#include <Eigen/Dense>

namespace surfscatter::reference {

struct BandedMatrix {
    std::size_t n = 0, band = 0;
    std::vector<std::complex<double>> data;  // row i holds columns i - band .. i + band
    BandedMatrix() = default;
    BandedMatrix(std::size_t size, std::size_t half_width);
    std::complex<double>& at(std::size_t i, std::size_t j) { return data[i * (2 * band + 1) + j + band - i]; }
    std::complex<double> at(std::size_t i, std::size_t j) const { return data[i * (2 * band + 1) + j + band - i]; }
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
