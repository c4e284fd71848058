#include "profile_surface_options.hpp"

#include "surfscatter/core/error.hpp"

namespace surfscatter::cli {

void SurfaceArgs::add_to(CLI::App* sub, const char* psd_help) {
    sub->add_option("--psd", psd, psd_help)->check(CLI::IsMember({"kc", "gaussian"}));
    sub->add_option("--sigma", sigma, "rms height sigma_h (um), with --psd");
    sub->add_option("--corr-length", corr_length, "correlation length (um), with --psd");
    sub->add_option("--gamma", gamma, "KC exponent gamma > 1, with --psd kc");
}

std::unique_ptr<surface::RadialStatistics> statistics_from(const SurfaceArgs& a) {
    if (!a.sigma || !a.corr_length) fail("--psd {} needs --sigma and --corr-length", *a.psd);
    surface::require_surface_length(*a.sigma, "--sigma");
    surface::require_surface_length(*a.corr_length, "--corr-length");
    if (*a.psd == "kc") {
        if (!a.gamma) fail("--gamma is required for --psd kc");
        surface::require_kc_gamma(*a.gamma, "--gamma");
        return std::make_unique<surface::KCorrelation>(*a.sigma, *a.corr_length, *a.gamma);
    }
    if (a.gamma) fail("--gamma applies to --psd kc only");
    return std::make_unique<surface::GaussianAcv>(*a.sigma, *a.corr_length);
}

}  // namespace surfscatter::cli
