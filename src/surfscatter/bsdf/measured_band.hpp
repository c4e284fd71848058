#pragma once
// psd measured: the frequencies the measurement resolves. A direction wo whose first-order frequency k (wo + wi)_xy
// lies beyond them (periods shorter than two pixels, or than two of a profile's spacings) draws on nothing that was
// measured: only the self-convolutions reach there, so its value says nothing about the surface. `brdf eval`,
// `brdf slice` and Python's Bsdf.eval count such directions and warn once with the count (beyond_band_warning).
#include <cstddef>
#include <optional>
#include <string>

#include "surfscatter/bsdf/model_options.hpp"
#include "surfscatter/math/vec.hpp"

namespace surfscatter::bsdf {

// |zeta_x| <= nyquist_x and |zeta_y| <= nyquist_y (a map's lattice), or |zeta| <= nyquist_x (a profile's disc: its
// surface is isotropic by assumption), rad/um.
struct MeasuredBand {
    double nyquist_x = 0, nyquist_y = 0;
    bool disc = false;
    std::string source;  // the file (or "the measured statistics")

    bool beyond(const Vec3& wi, const Vec3& wo, double lambda_nm) const;
};

// The band of psd measured surfaces (a prepared map, measured statistics given, or a profile's); nullopt otherwise.
std::optional<MeasuredBand> measured_band(const SurfaceOptions& surface);

// One warning line for `beyond` of `total` directions beyond the band at lambda_nm (starting "warning: "), or "" when
// beyond is 0.
std::string beyond_band_warning(const MeasuredBand& band, std::size_t beyond, std::size_t total, double lambda_nm);

}  // namespace surfscatter::bsdf
