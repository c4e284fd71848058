#pragma once
// Elliptical (anisotropic) statistics, THEORY 7.1, docs/SURFACE.md "Anisotropy":
//   C(x_u, x_v) = sigma^2 rho_1(sqrt((x_u / LU)^2 + (x_v / LV)^2)),
//   x_u = x cos A + y sin A,  x_v = -x sin A + y cos A   (local frame, x towards phi = 0; A the lay angle),
// rho_1 the normalised ACV of the isotropic statistics `radial` at correlation length 1; `radial` itself has
// correlation length LU, so C(x) = sigma^2 rho_radial(|(x_u, x_v / s)|) with the stretch s = LV / LU.
// Fourier scaling: P-hat(zeta) = s P-hat_radial(|(zeta_u, s zeta_v)|), and as C^m stretches as C does, every
// self-convolution order P-hat^{*m} is the same stretch of the radial one's: the isotropic lobe tables serve, read at
// the stretched radius, times s. LV = LU is the isotropic surface itself (every result unchanged).
// The lay direction u is where the surface is correlated over LU: for a brushed plate with LV < LU, u runs along the
// brushing marks and v across them.
#include <memory>
#include <string>

#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface {

class EllipticalStatistics {
public:
    // `radial` (sigma_h, ACV shape, LU = radial->correlation_length()), LV in um (user range, require_surface_length),
    // A in radians (finite). Throws Error naming the bad value.
    EllipticalStatistics(std::shared_ptr<const RadialStatistics> radial, double corr_length_v_um, double lay_angle_rad);

    const RadialStatistics& radial() const { return *radial_; }
    const std::shared_ptr<const RadialStatistics>& radial_ptr() const { return radial_; }
    double sigma_h() const { return radial_->sigma_h(); }
    double corr_length_u() const { return radial_->correlation_length(); }
    double corr_length_v() const { return corr_length_v_; }
    double stretch() const { return stretch_; }        // s = LV / LU
    double lay_angle() const { return lay_angle_; }    // A, radians
    bool isotropic() const { return stretch_ == 1.0; }

    // (u, v) components of a local-frame vector (x, y), and back.
    Vec2 to_lay(Vec2 xy) const { return {cos_ * xy.x + sin_ * xy.y, -sin_ * xy.x + cos_ * xy.y}; }
    Vec2 from_lay(Vec2 uv) const { return {cos_ * uv.x - sin_ * uv.y, sin_ * uv.x + cos_ * uv.y}; }
    // |(zeta_u, s zeta_v)|: the radius at which the radial statistics (and its tables) are read for zeta = (x, y).
    double stretched_radius(Vec2 zeta_xy) const;
    // P-hat(zeta) (um^2, unit mass over the zeta-plane) and rho(x, y) = C / sigma^2, local frame.
    double psd_unit(Vec2 zeta_xy) const { return stretch_ * radial_->psd_unit(stretched_radius(zeta_xy)); }
    double acv_normalized(Vec2 r_xy) const;
    // <h_u^2>, <h_v^2> (dimensionless; <h_u h_v> = 0): half the radial mean-square slope, divided by 1 and s^2
    // (THEORY 7.1). +inf where the radial one diverges (KC gamma <= 3).
    Vec2 slope_variances_lay() const;
    // The radial key with LV and A: tables derived from the anisotropic surface.
    std::string cache_key() const;
    // The radial key with LV but not A: tables over the incidence relative to the lay (phi_i - A), which a new lay
    // angle only rotates (AnisotropicGhsBsdf's), are shared by every lay angle.
    std::string shape_key() const;

private:
    std::shared_ptr<const RadialStatistics> radial_;
    double corr_length_v_, stretch_, lay_angle_, cos_, sin_;
};

}  // namespace surfscatter::surface
