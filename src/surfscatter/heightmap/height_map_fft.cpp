#include "surfscatter/heightmap/height_map_fft.hpp"

#include <fftw3.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/fftw_planner.hpp"

namespace surfscatter::heightmap {

namespace {

class Plan {
public:
    explicit Plan(fftw_plan plan) : plan_(plan) {
        if (!plan_) fail("FFTW could not create a plan");
    }
    ~Plan() {
        std::lock_guard lock(fftw_planner_mutex());
        fftw_destroy_plan(plan_);
    }
    Plan(const Plan&) = delete;
    Plan& operator=(const Plan&) = delete;
    void execute() const { fftw_execute(plan_); }

private:
    fftw_plan plan_;
};
}  // namespace

std::vector<std::complex<double>> forward_fft_2d(const std::vector<double>& data, std::size_t nx, std::size_t ny) {
    std::vector<double> input = data;  // FFTW wants a mutable input array
    std::vector<std::complex<double>> spectrum(ny * (nx / 2 + 1));
    fftw_plan raw;
    {
        std::lock_guard lock(fftw_planner_mutex());
        raw = fftw_plan_dft_r2c_2d(static_cast<int>(ny), static_cast<int>(nx), input.data(),
                                   reinterpret_cast<fftw_complex*>(spectrum.data()), FFTW_ESTIMATE);
    }
    Plan(raw).execute();
    return spectrum;
}

std::vector<double> inverse_fft_2d(std::vector<std::complex<double>> spectrum, std::size_t nx, std::size_t ny) {
    std::vector<double> output(nx * ny);
    fftw_plan raw;
    {
        std::lock_guard lock(fftw_planner_mutex());
        raw = fftw_plan_dft_c2r_2d(static_cast<int>(ny), static_cast<int>(nx),
                                   reinterpret_cast<fftw_complex*>(spectrum.data()), output.data(), FFTW_ESTIMATE);
    }
    Plan(raw).execute();
    return output;
}

std::vector<double> linear_autocorrelation(const std::vector<double>& values, std::size_t nx, std::size_t ny) {
    const std::size_t ex = 2 * nx, ey = 2 * ny;
    std::vector<double> padded(ex * ey, 0.0);
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix) padded[iy * ex + ix] = values[iy * nx + ix];
    auto spectrum = forward_fft_2d(padded, ex, ey);
    const double norm = 1.0 / static_cast<double>(ex * ey);
    for (auto& c : spectrum) c = std::norm(c) * norm;
    return inverse_fft_2d(std::move(spectrum), ex, ey);
}

}  // namespace surfscatter::heightmap
