#include "surfscatter/reference/banded_solve.hpp"

#include <algorithm>
#include <limits>

#include "surfscatter/core/error.hpp"

extern "C" {
void zgbtrf_(const int* m, const int* n, const int* kl, const int* ku, std::complex<double>* ab, const int* ldab,
             int* ipiv, int* info);
void zgbtrs_(const char* trans, const int* n, const int* kl, const int* ku, const int* nrhs,
             const std::complex<double>* ab, const int* ldab, const int* ipiv, std::complex<double>* b, const int* ldb,
             int* info);
}

namespace surfscatter::reference {

BandedMatrix::BandedMatrix(std::size_t size, std::size_t half_width)
    : n(size), band(half_width), data(size * (2 * half_width + 1), std::complex<double>(0.0)) {}

Eigen::VectorXcd BandedMatrix::multiply(const Eigen::VectorXcd& v) const {
    Eigen::VectorXcd out(static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t lo = i > band ? i - band : 0, hi = std::min(i + band + 1, n);
        out[static_cast<Eigen::Index>(i)] = dot_segment(&at(i, lo), v.data() + lo, hi - lo);
    }
    return out;
}

BandedMatrix BandedMatrix::truncated(std::size_t half_width) const {
    BandedMatrix out(n, std::min(half_width, band));
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i > out.band ? i - out.band : 0; j < std::min(i + out.band + 1, n); ++j) out.at(i, j) = at(i, j);
    return out;
}

BandedLu::BandedLu(const BandedMatrix& a, std::string_view what) {
    if (a.n > static_cast<std::size_t>(std::numeric_limits<int>::max() / 4))
        fail("{}: {} unknowns exceed LAPACK's int", what, a.n);
    n_ = static_cast<int>(a.n);
    band_ = static_cast<int>(std::min(a.band, a.n > 0 ? a.n - 1 : 0));
    ldab_ = 3 * band_ + 1;  // LAPACK's layout: kl extra rows for the pivoting's fill-in
    factors_.assign(static_cast<std::size_t>(ldab_) * a.n, std::complex<double>(0.0));
    const auto b = static_cast<std::size_t>(band_);
    for (std::size_t j = 0; j < a.n; ++j)
        for (std::size_t i = j > b ? j - b : 0; i < std::min(j + b + 1, a.n); ++i)
            factors_[j * static_cast<std::size_t>(ldab_) + 2 * b + i - j] = a.at(i, j);
    pivots_.resize(a.n);
    int info = 0;
    zgbtrf_(&n_, &n_, &band_, &band_, factors_.data(), &ldab_, pivots_.data(), &info);
    if (info > 0) fail("{} is singular: pivot {} of {} is zero", what, info, n_);
    if (info < 0) fail("{}: zgbtrf rejected argument {}", what, -info);
}

Eigen::VectorXcd BandedLu::solve(Eigen::VectorXcd b) const {
    const char no_transpose = 'N';
    const int one = 1;
    int info = 0;
    zgbtrs_(&no_transpose, &n_, &band_, &band_, &one, factors_.data(), &ldab_, pivots_.data(), b.data(), &n_, &info);
    if (info < 0) fail("banded solve: zgbtrs rejected argument {}", -info);
    return b;
}

}  // namespace surfscatter::reference
