#include "surfscatter/reference/gmres.hpp"

#include <cmath>
#include <complex>
#include <vector>

namespace surfscatter::reference {

GmresResult gmres(const LinearOperator& apply, const LinearOperator& preconditioner, const Eigen::VectorXcd& b,
                  double tolerance, int restart, int max_iterations) {
    using Complex = std::complex<double>;
    GmresResult out;
    const Eigen::Index n = b.size();
    out.x = Eigen::VectorXcd::Zero(n);
    const double b_norm = b.norm();
    if (b_norm == 0.0) {
        out.converged = true;
        return out;
    }
    Eigen::VectorXcd r = b;
    while (out.iterations < max_iterations) {
        const double beta = r.norm();
        if (beta <= tolerance * b_norm) break;
        const int m = restart;
        Eigen::MatrixXcd v(n, m + 1);
        Eigen::MatrixXcd h = Eigen::MatrixXcd::Zero(m + 1, m);
        std::vector<Complex> cs(static_cast<std::size_t>(m)), sn(static_cast<std::size_t>(m));
        Eigen::VectorXcd g = Eigen::VectorXcd::Zero(m + 1);
        g[0] = beta;
        v.col(0) = r / beta;
        int steps = 0;
        for (int j = 0; j < m && out.iterations < max_iterations; ++j) {
            Eigen::VectorXcd w = apply(preconditioner(v.col(j)));
            ++out.iterations;
            for (int i = 0; i <= j; ++i) {  // modified Gram-Schmidt
                h(i, j) = v.col(i).dot(w);
                w -= h(i, j) * v.col(i);
            }
            h(j + 1, j) = w.norm();
            if (std::abs(h(j + 1, j)) > 0.0) v.col(j + 1) = w / h(j + 1, j);
            for (int i = 0; i < j; ++i) {  // earlier Givens rotations
                const Complex t = cs[i] * h(i, j) + sn[i] * h(i + 1, j);
                h(i + 1, j) = -std::conj(sn[i]) * h(i, j) + cs[i] * h(i + 1, j);
                h(i, j) = t;
            }
            const double denom = std::hypot(std::abs(h(j, j)), std::abs(h(j + 1, j)));
            cs[j] = denom > 0 ? std::abs(h(j, j)) / denom : 1.0;
            sn[j] = denom > 0 ? (std::abs(h(j, j)) > 0 ? h(j, j) / std::abs(h(j, j)) : Complex(1.0)) *
                                    std::conj(h(j + 1, j)) / denom
                              : Complex(0.0);
            h(j, j) = cs[j] * h(j, j) + sn[j] * h(j + 1, j);
            h(j + 1, j) = 0.0;
            g[j + 1] = -std::conj(sn[j]) * g[j];
            g[j] = cs[j] * g[j];
            steps = j + 1;
            if (std::abs(g[j + 1]) <= 0.5 * tolerance * b_norm) break;  // margin for the recomputed residual
        }
        const Eigen::VectorXcd y = h.topLeftCorner(steps, steps).triangularView<Eigen::Upper>().solve(g.head(steps));
        out.x += preconditioner(v.leftCols(steps) * y);
        r = b - apply(out.x);
        ++out.iterations;
    }
    out.relative_residual = r.norm() / b_norm;
    out.converged = out.relative_residual <= tolerance;
    return out;
}

}  // namespace surfscatter::reference
