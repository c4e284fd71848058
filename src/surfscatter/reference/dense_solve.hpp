#pragma once
// Dense complex linear solves of the exact solvers, by LAPACK's zgetrf / zgetrs (LU with partial pivoting, backward
// stable as Eigen's PartialPivLU, which it replaces). Why LAPACK and not Eigen: Debian's liblapack.so.3 resolves to
// OpenBLAS (scripts/install-deps installs its serial build), whose kernels are chosen for the CPU at run time; at
// 1,820 unknowns it factors 5-6x faster than Eigen compiled for baseline x86-64 (docs/PERFORMANCE.md, "Exact 1-D
// reference"). The serial build keeps one thread per solve, so parallel realizations do not oversubscribe the cores.
// With the reference LAPACK instead the results are the same and the solve slower.
#include <string_view>

#include <Eigen/Dense>

namespace surfscatter::reference {

// x with a x = b; `what` names the system in the error thrown when a is exactly singular.
Eigen::VectorXcd solve_dense(Eigen::MatrixXcd a, Eigen::VectorXcd b, std::string_view what);

}  // namespace surfscatter::reference
