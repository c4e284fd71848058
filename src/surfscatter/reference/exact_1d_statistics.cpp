#include "surfscatter/reference/exact_1d_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/reference/parallel_jobs.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace surfscatter::reference {

Profile random_profile(const surface::RadialStatistics& statistics, const Exact1dOptions& options, double length_um,
                       std::uint64_t seed) {
    require_positive(length_um, "profile length (um)");
    require_positive(options.lambda_nm, "wavelength (nm)");
    const double spacing = options.lambda_nm * 1e-3 / options.points_per_wavelength;
    const double samples = std::ceil(length_um / spacing) + 1;
    if (!(samples <= kMaxExact1dNodes))
        fail("profile length {} um needs {:.3g} samples, more than {:.0e}", length_um, samples, kMaxExact1dNodes);
    const auto n = static_cast<std::size_t>(samples);
    Profile profile;
    profile.spacing_um = spacing;
    profile.x0_um = -0.5 * spacing * static_cast<double>(n - 1);
    profile.h_um = surface::synthesize_profile(statistics, n, spacing, seed);
    return profile;
}

StatisticalResult solve_exact_1d_statistics(const surface::RadialStatistics& statistics,
                                            const material::Conductor& conductor, const Exact1dOptions& options,
                                            const StatisticalOptions& st) {
    if (st.realizations < 2) fail("realizations must be at least 2 (for a standard error), got {}", st.realizations);
    // The first profile is made before any thread starts, so that bad statistics or lengths fail at once.
    const Profile first = random_profile(statistics, options, st.length_um, st.seed);
    // Every realization's far field is kept until the end (the standard errors): bounded before allocating.
    const double field_bytes = sizeof(FarField) + 1.0 + (kFarFieldSteps + 1.0) * (sizeof(double) + sizeof(std::complex<double>));
    require_memory(field_bytes * static_cast<double>(st.realizations),
                   fmt::format("keeping the far fields of {} realizations", st.realizations));
    std::vector<FarField> fields(st.realizations);
    const std::vector<char> done =
        run_parallel_jobs(st.realizations, st.threads, "exact-1d realizations", st.progress, [&] {
            return [&](std::size_t r) {
                const Profile profile = r == 0 ? first : random_profile(statistics, options, st.length_um, st.seed + r);
                fields[r] = solve_exact_1d(profile, conductor, options);
            };
        });

    StatisticalResult out;
    std::vector<const FarField*> completed;
    for (std::size_t r = 0; r < st.realizations; ++r)
        if (done[r]) completed.push_back(&fields[r]);
    out.realizations = completed.size();
    if (completed.empty()) return out;
    const std::size_t m = completed.front()->amplitude.size();
    const double count = static_cast<double>(completed.size());
    out.theta_o_rad = completed.front()->theta_o_rad;
    out.intensity.assign(m, 0.0);
    out.coherent.assign(m, 0.0);
    out.incoherent.assign(m, 0.0);
    out.coherent_stderr.assign(m, 0.0);
    out.incoherent_stderr.assign(m, 0.0);
    for (std::size_t j = 0; j < m; ++j) {
        std::complex<double> mean = 0.0;
        double mean_intensity = 0.0;
        for (const FarField* f : completed) {
            mean += f->amplitude[j];
            mean_intensity += std::norm(f->amplitude[j]);
        }
        mean /= count;
        mean_intensity /= count;
        out.intensity[j] = mean_intensity;
        out.coherent[j] = std::norm(mean);
        out.incoherent[j] = std::max(0.0, mean_intensity - out.coherent[j]);
        // Standard errors by the delta method: the coherent part moves with the amplitude's component along its
        // mean (2 |<a>| Re(a conj(<a>)/|<a>|)), the incoherent part with |a|^2 - 2 Re(a conj(<a>)).
        if (completed.size() < 2) continue;
        double var_coherent = 0.0, var_incoherent = 0.0;
        const double mean_abs = std::abs(mean);
        const std::complex<double> direction = mean_abs > 0 ? std::conj(mean) / mean_abs : 0.0;
        const double mean_projection = (mean * direction).real();
        const double mean_influence = mean_intensity - 2.0 * out.coherent[j];
        for (const FarField* f : completed) {
            const std::complex<double> a = f->amplitude[j];
            const double p = (a * direction).real() - mean_projection;
            const double q = std::norm(a) - 2.0 * (a * std::conj(mean)).real() - mean_influence;
            var_coherent += p * p;
            var_incoherent += q * q;
        }
        var_coherent /= count - 1.0;
        var_incoherent /= count - 1.0;
        out.coherent_stderr[j] = 2.0 * mean_abs * std::sqrt(var_coherent / count);
        out.incoherent_stderr[j] = std::sqrt(var_incoherent / count);
    }
    return out;
}

}  // namespace surfscatter::reference
