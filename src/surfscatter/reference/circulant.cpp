#include "surfscatter/reference/circulant.hpp"

#include <complex>
#include <mutex>

#include <fftw3.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/fftw_planner.hpp"

namespace surfscatter::reference {

namespace {

void execute(fftw_plan plan, const Eigen::VectorXcd& in, Eigen::VectorXcd& out) {
    fftw_execute_dft(plan, reinterpret_cast<fftw_complex*>(const_cast<std::complex<double>*>(in.data())),
                     reinterpret_cast<fftw_complex*>(out.data()));
}

}  // namespace

std::size_t padded_fft_size(std::size_t nodes) {
    std::size_t size = 1;
    while (size < 2 * nodes) size *= 2;
    return size;
}

struct Circulant::Plans {
    fftw_plan forward = nullptr, backward = nullptr;
    ~Plans() {
        const std::lock_guard lock(heightmap::fftw_planner_mutex());
        if (forward) fftw_destroy_plan(forward);
        if (backward) fftw_destroy_plan(backward);
    }
};

Circulant::Circulant(const Eigen::VectorXcd& column)
    : symbol_(column.size()), plans_(std::make_unique<Plans>()), padded_(column.size()), spectrum_(column.size()) {
    const auto size = static_cast<int>(column.size());
    {
        const std::lock_guard lock(heightmap::fftw_planner_mutex());
        // Out of place, on 16-byte aligned Eigen vectors like every array they run on (SIMD codelets allowed).
        auto* in = reinterpret_cast<fftw_complex*>(padded_.data());
        auto* out = reinterpret_cast<fftw_complex*>(spectrum_.data());
        plans_->forward = fftw_plan_dft_1d(size, in, out, FFTW_FORWARD, FFTW_ESTIMATE);
        plans_->backward = fftw_plan_dft_1d(size, in, out, FFTW_BACKWARD, FFTW_ESTIMATE);
    }
    execute(plans_->forward, column, symbol_);
}

Circulant::~Circulant() = default;

Eigen::VectorXcd Circulant::solve_head(const Eigen::VectorXcd& v) const {
    const Eigen::Index size = symbol_.size(), n = v.size();
    padded_.head(n) = v;
    padded_.tail(size - n).setZero();
    execute(plans_->forward, padded_, spectrum_);
    for (Eigen::Index q = 0; q < size; ++q) {
        if (symbol_[q] == std::complex<double>(0.0)) fail("circulant solve: the symbol vanishes at frequency {}", q);
        spectrum_[q] /= symbol_[q] * static_cast<double>(size);
    }
    execute(plans_->backward, spectrum_, padded_);
    return padded_.head(n);
}

Eigen::VectorXcd Circulant::column() const {
    Eigen::VectorXcd out(symbol_.size());
    execute(plans_->backward, symbol_, out);
    return out / static_cast<double>(symbol_.size());
}

}  // namespace surfscatter::reference
