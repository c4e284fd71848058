#pragma once
// Builds a scattering model from its options, validating every option first (throws surfscatter::Error naming the
// option and the bad value, e.g. "gamma must be > 1, got 0.8").
#include <memory>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/bsdf/model_options.hpp"

namespace surfscatter::bsdf {

void validate(const ModelOptions& options);
std::unique_ptr<Bsdf> make_bsdf(const ModelOptions& options);

// Reads surface.surface_file (if psd = file and it is not read yet) into surface.height_map, so that a front end
// can report on it (surface::describe) and make_bsdf does not read it again.
void load_height_map(SurfaceOptions& surface);

}  // namespace surfscatter::bsdf
