#pragma once
// Restarted GMRES with right preconditioning for the exact 1-D solver's iterative route (docs/REFERENCE.md,
// "Solve"). Written here rather than taken from Eigen's unsupported IterativeSolvers because the operator is a
// function (near band plus FFT far part), not a matrix, and that module wants a sparse-matrix wrapper around it.
#include <functional>

#include <Eigen/Dense>

namespace surfscatter::reference {

using LinearOperator = std::function<Eigen::VectorXcd(const Eigen::VectorXcd&)>;

struct GmresResult {
    Eigen::VectorXcd x;
    int iterations = 0;          // operator applications
    double relative_residual = 0.0;  // |b - A x| / |b|, recomputed from x at the end
    bool converged = false;
};

// Solves A x = b to |b - A x| <= tolerance |b|, with A M^-1 y = b, x = M^-1 y (`preconditioner` applies M^-1),
// restarting every `restart` steps, giving up after `max_iterations` operator applications.
GmresResult gmres(const LinearOperator& apply, const LinearOperator& preconditioner, const Eigen::VectorXcd& b,
                  double tolerance, int restart, int max_iterations);

}  // namespace surfscatter::reference
