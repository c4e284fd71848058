#include "surfscatter/bsdf/measured_band.hpp"

#include <cmath>

#include <fmt/format.h>

namespace surfscatter::bsdf {

bool MeasuredBand::beyond(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    const double k = kTwoPi / (lambda_nm * 1e-3);
    const double zx = k * (wo.x + wi.x), zy = k * (wo.y + wi.y);
    return disc ? std::hypot(zx, zy) > nyquist_x : std::abs(zx) > nyquist_x || std::abs(zy) > nyquist_y;
}

std::optional<MeasuredBand> measured_band(const SurfaceOptions& s) {
    if (s.psd != PsdKind::measured) return std::nullopt;
    const std::string source = s.surface_file.empty() ? "the measured statistics" : s.surface_file;
    if (s.measured_profile) return MeasuredBand{s.measured_profile->nyquist(), s.measured_profile->nyquist(), true, source};
    if (s.measured_psd) {
        const surface::Psd2d& p = s.measured_psd->spectrum();
        return MeasuredBand{0.5 * p.dzeta_x * static_cast<double>(p.nx), 0.5 * p.dzeta_y * static_cast<double>(p.ny),
                            false, source};
    }
    if (s.prepared)
        return MeasuredBand{kPi / s.prepared->map.spacing_x(), kPi / s.prepared->map.spacing_y(), false, source};
    return std::nullopt;
}

std::string beyond_band_warning(const MeasuredBand& band, std::size_t beyond, std::size_t total, double lambda_nm) {
    if (beyond == 0) return "";
    return fmt::format(
        "warning: {} of {} directions lie beyond the frequencies {} resolves ({} at {:.6g} nm: periods shorter than "
        "two {}): the measured spectrum holds nothing there, so their values say nothing about the surface (a finer "
        "{}, or --psd file for the KC fitted to it, extrapolated)",
        beyond, total, band.source,
        band.disc ? fmt::format("|zeta| > {:.3g} rad/um", band.nyquist_x)
                  : fmt::format("|zeta_x| > {:.3g} or |zeta_y| > {:.3g} rad/um", band.nyquist_x, band.nyquist_y),
        lambda_nm, band.disc ? "of the profile's spacings" : "pixels", band.disc ? "profile" : "map");
}

}  // namespace surfscatter::bsdf
