#include "surfscatter/reference/circulant.hpp"

#include <complex>
#include <mutex>

#include <fftw3.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/fftw_planner.hpp"

namespace surfscatter::reference {

std::size_t padded_fft_size(std::size_t nodes) {
    std::size_t size = 1;
    while (size < 2 * nodes) size *= 2;
    return size;
}

struct FftPlans::Plans {
    fftw_plan forward = nullptr, backward = nullptr;
    ~Plans() {
        const std::lock_guard lock(heightmap::fftw_planner_mutex());
        if (forward) fftw_destroy_plan(forward);
        if (backward) fftw_destroy_plan(backward);
    }
};

FftPlans::FftPlans(std::size_t size) : plans_(std::make_unique<Plans>()) {
    const std::lock_guard lock(heightmap::fftw_planner_mutex());
    Eigen::VectorXcd in(static_cast<Eigen::Index>(size)), out(static_cast<Eigen::Index>(size));
    auto* raw_in = reinterpret_cast<fftw_complex*>(in.data());
    auto* raw_out = reinterpret_cast<fftw_complex*>(out.data());
    plans_->forward = fftw_plan_dft_1d(static_cast<int>(size), raw_in, raw_out, FFTW_FORWARD, FFTW_ESTIMATE);
    plans_->backward = fftw_plan_dft_1d(static_cast<int>(size), raw_in, raw_out, FFTW_BACKWARD, FFTW_ESTIMATE);
}

FftPlans::~FftPlans() = default;

namespace {

void execute(fftw_plan plan, const Eigen::VectorXcd& in, Eigen::VectorXcd& out) {
    fftw_execute_dft(plan, reinterpret_cast<fftw_complex*>(const_cast<std::complex<double>*>(in.data())),
                     reinterpret_cast<fftw_complex*>(out.data()));
}

}  // namespace

void FftPlans::forward(const Eigen::VectorXcd& in, Eigen::VectorXcd& out) const { execute(plans_->forward, in, out); }
void FftPlans::backward(const Eigen::VectorXcd& in, Eigen::VectorXcd& out) const { execute(plans_->backward, in, out); }

Circulant::Circulant(const Eigen::VectorXcd& column)
    : symbol_(column.size()), plans_(static_cast<std::size_t>(column.size())), padded_(column.size()),
      spectrum_(column.size()) {
    plans_.forward(column, symbol_);
}

Eigen::VectorXcd Circulant::solve_head(const Eigen::VectorXcd& v) const {
    const Eigen::Index size = symbol_.size(), n = v.size();
    padded_.head(n) = v;
    padded_.tail(size - n).setZero();
    plans_.forward(padded_, spectrum_);
    for (Eigen::Index q = 0; q < size; ++q) {
        if (symbol_[q] == std::complex<double>(0.0)) fail("circulant solve: the symbol vanishes at frequency {}", q);
        spectrum_[q] /= symbol_[q] * static_cast<double>(size);
    }
    plans_.backward(spectrum_, padded_);
    return padded_.head(n);
}

Eigen::VectorXcd Circulant::column() const {
    Eigen::VectorXcd out(symbol_.size());
    plans_.backward(symbol_, out);
    return out / static_cast<double>(symbol_.size());
}

}  // namespace surfscatter::reference
