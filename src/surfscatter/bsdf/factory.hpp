#pragma once
// Builds a scattering model from its options, validating every option first (throws surfscatter::Error naming the
// option and the bad value, e.g. "gamma must be > 1, got 0.8"). A height map (psd file or measured) is read once per
// model. `notes`, if given, receives what the user should know about the result without it being an error: for a
// measured PSD, the range the data cover and how it is extrapolated beyond.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/bsdf/model_options.hpp"

namespace surfscatter::bsdf {

void validate(const ModelOptions& options);
std::unique_ptr<Bsdf> make_bsdf(const ModelOptions& options, std::vector<std::string>* notes = nullptr);

// Reads surface.surface_file (if psd = file or measured and no map is prepared yet; or takes surface.height_map) and
// prepares it as surface.preparation asks (heightmap/prepare.hpp) into surface.prepared, so that a front end can report on it and
// make_bsdf does not read it again.
void load_height_map(SurfaceOptions& surface);

// What the models say of a loaded map's preparation: its steps (heightmap::describe) and, when it has outliers, what
// was done with them (a warning when kept ones hold most of its pixel-scale roughness).
std::vector<std::string> preparation_notes(const SurfaceOptions& surface);

}  // namespace surfscatter::bsdf
