#pragma once
// FFTs of one length, and circulant matrices by them: the far series and the flat-surface preconditioner of the
// exact 1-D solver's iterative route (docs/REFERENCE.md, "Solve"). A circulant of size L has (C v)_i = sum_j c((i - j) mod L) v_j and the eigenvalues
// FFT(c), its symbol; products and inverses of circulants are those of their symbols.
#include <cstddef>
#include <memory>

#include <Eigen/Dense>

namespace surfscatter::reference {

// The FFT length that holds the interactions of n nodes without wrap-around: the power of 2 >= 2 n.
std::size_t padded_fft_size(std::size_t nodes);

// A forward and a backward out-of-place FFTW plan of one length (unnormalised). Out of place because in place,
// FFTW_ESTIMATE transposes at 4096; every array they run on is an Eigen vector of complex<double>, 16-byte aligned,
// so the plans may use SIMD codelets (FFTW_UNALIGNED forbids them: far products took 1.3x longer with it,
// docs/PERFORMANCE.md). Made and destroyed under heightmap::fftw_planner_mutex(); executing is thread-safe.
class FftPlans {
public:
    explicit FftPlans(std::size_t size);
    ~FftPlans();
    FftPlans(const FftPlans&) = delete;
    FftPlans& operator=(const FftPlans&) = delete;
    // out = FFT(in), both of the plans' length.
    void forward(const Eigen::VectorXcd& in, Eigen::VectorXcd& out) const;
    void backward(const Eigen::VectorXcd& in, Eigen::VectorXcd& out) const;

private:
    struct Plans;
    std::unique_ptr<Plans> plans_;
};

class Circulant {
public:
    // column: c(0 .. L - 1), L a power of 2.
    explicit Circulant(const Eigen::VectorXcd& column);

    Eigen::VectorXcd& symbol() { return symbol_; }
    const Eigen::VectorXcd& symbol() const { return symbol_; }
    // The first v.size() entries of C^-1 [v; 0] (v no longer than L). Throws Error where the symbol vanishes.
    Eigen::VectorXcd solve_head(const Eigen::VectorXcd& v) const;
    // c(d) for d = 0 .. L - 1 from the symbol (the inverse FFT).
    Eigen::VectorXcd column() const;

private:
    Eigen::VectorXcd symbol_;
    FftPlans plans_;
    mutable Eigen::VectorXcd padded_, spectrum_;
};

}  // namespace surfscatter::reference
