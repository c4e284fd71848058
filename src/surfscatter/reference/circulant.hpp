#pragma once
// Circulant matrices by FFT: the flat-surface preconditioner of the exact 1-D solver's iterative route
// (docs/REFERENCE.md, "Solve"). A circulant of size L has (C v)_i = sum_j c((i - j) mod L) v_j and the eigenvalues
// FFT(c), its symbol; products and inverses of circulants are those of their symbols.
#include <cstddef>
#include <memory>

#include <Eigen/Dense>

namespace surfscatter::reference {

// The FFT length that holds the interactions of n nodes without wrap-around: the power of 2 >= 2 n.
std::size_t padded_fft_size(std::size_t nodes);

class Circulant {
public:
    // column: c(0 .. L - 1), L a power of 2.
    explicit Circulant(const Eigen::VectorXcd& column);
    ~Circulant();
    Circulant(const Circulant&) = delete;
    Circulant& operator=(const Circulant&) = delete;

    Eigen::VectorXcd& symbol() { return symbol_; }
    const Eigen::VectorXcd& symbol() const { return symbol_; }
    // The first v.size() entries of C^-1 [v; 0] (v no longer than L). Throws Error where the symbol vanishes.
    Eigen::VectorXcd solve_head(const Eigen::VectorXcd& v) const;
    // c(d) for d = 0 .. L - 1 from the symbol (the inverse FFT).
    Eigen::VectorXcd column() const;

private:
    struct Plans;
    Eigen::VectorXcd symbol_;
    std::unique_ptr<Plans> plans_;
    mutable Eigen::VectorXcd padded_, spectrum_;
};

}  // namespace surfscatter::reference
