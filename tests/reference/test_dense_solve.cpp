#include "surfscatter/reference/dense_solve.hpp"

#include <gtest/gtest.h>

#include "surfscatter/core/error.hpp"

namespace surfscatter::reference {
namespace {

// Against a system whose solution is chosen first: a diagonally weighted random complex matrix of the exact solver's
// size class, b = a x, so the check needs no second solver.
TEST(DenseSolve, RecoversAChosenSolution) {
    const Eigen::Index n = 300;
    Eigen::MatrixXcd a = Eigen::MatrixXcd::Random(n, n);
    a.diagonal().array() += std::complex<double>(3.0, -1.0);
    const Eigen::VectorXcd x = Eigen::VectorXcd::Random(n);
    const Eigen::VectorXcd solved = solve_dense(a, a * x, "the test system");
    EXPECT_LT((solved - x).norm() / x.norm(), 1e-12);
}

TEST(DenseSolve, NamesASingularSystem) {
    Eigen::MatrixXcd a = Eigen::MatrixXcd::Identity(4, 4);
    a.row(2).setZero();
    try {
        solve_dense(a, Eigen::VectorXcd::Ones(4), "the test system");
        FAIL() << "a singular system was solved";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("the test system is singular: pivot 3 of 4"), std::string::npos) << e.what();
    }
}

TEST(DenseSolve, RefusesMismatchedSizes) {
    EXPECT_THROW(solve_dense(Eigen::MatrixXcd::Identity(3, 3), Eigen::VectorXcd::Ones(4), "the test system"), Error);
}

}  // namespace
}  // namespace surfscatter::reference
