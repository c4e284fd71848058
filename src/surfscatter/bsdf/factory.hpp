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

// Reads surface.surface_file (if psd = file or measured and it is not read yet) into surface.height_map, so that a
// front end can report on it (heightmap::describe) and make_bsdf does not read it again; with outliers fill, the map's
// outliers are then filled (once: surface.filled_outliers says what was).
void load_height_map(SurfaceOptions& surface);

// A loaded height map's outliers (heightmap/outliers.hpp): those load_height_map filled, else found now.
heightmap::Outliers outliers_of(const SurfaceOptions& surface);
// The models' note on them: what outliers fill filled, or, kept, how many there are and their share of the map's
// pixel-scale roughness (a warning when they hold most of it); nothing for a map without any.
std::optional<std::string> outlier_note(const SurfaceOptions& surface, const heightmap::Outliers& outliers);

}  // namespace surfscatter::bsdf
