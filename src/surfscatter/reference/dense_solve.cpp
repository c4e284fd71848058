#include "surfscatter/reference/dense_solve.hpp"

#include <complex>
#include <limits>
#include <vector>

#include "surfscatter/core/error.hpp"

extern "C" {
void zgetrf_(const int* m, const int* n, std::complex<double>* a, const int* lda, int* ipiv, int* info);
void zgetrs_(const char* trans, const int* n, const int* nrhs, const std::complex<double>* a, const int* lda,
             const int* ipiv, std::complex<double>* b, const int* ldb, int* info);
}

namespace surfscatter::reference {

Eigen::VectorXcd solve_dense(Eigen::MatrixXcd a, Eigen::VectorXcd b, std::string_view what) {
    if (a.rows() != a.cols() || a.rows() != b.size())
        fail("{}: a {} x {} matrix against {} right-hand sides", what, a.rows(), a.cols(), b.size());
    if (a.rows() > std::numeric_limits<int>::max()) fail("{}: {} unknowns exceed LAPACK's int", what, a.rows());
    const int n = static_cast<int>(a.rows()), one = 1;
    std::vector<int> pivots(static_cast<std::size_t>(n));
    int info = 0;
    zgetrf_(&n, &n, a.data(), &n, pivots.data(), &info);
    if (info > 0) fail("{} is singular: pivot {} of {} is zero", what, info, n);
    if (info < 0) fail("{}: zgetrf rejected argument {}", what, -info);
    const char no_transpose = 'N';
    zgetrs_(&no_transpose, &n, &one, a.data(), &n, pivots.data(), b.data(), &n, &info);
    if (info < 0) fail("{}: zgetrs rejected argument {}", what, -info);
    return b;
}

}  // namespace surfscatter::reference
