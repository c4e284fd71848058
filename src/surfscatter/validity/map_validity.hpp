#pragma once
// Which 2-D model to trust for a height map or a synthesised surface (docs/VALIDITY.md, "Height maps"): every model
// bsdf::make_bsdf makes for the surface against the Kirchhoff BRDF of the map(s) (reference/kirchhoff_map.hpp), per
// wavelength and incidence (theta_i, phi_i). Unpolarised throughout (the reference averages s and p).
//
// The surface is a measured map (the models from psd measured, the map's own spectrum, and psd file, its KC fit) or
// KC / Gaussian statistics, elliptical with corr_length_v and lay_angle (the models from those statistics; the
// reference on `realizations` maps synthesised from them, surface/synthesis.hpp, seeds seed, seed + 1, ...).
// The reference is the mean of the maps' Kirchhoff BRDFs on their common direction lattice; its standard error per
// direction is the sub-areas' (reference::KirchhoffResult), combined over the maps as independent.
//
// Comparison (validity.hpp's criteria): the diffuse parts (the reference's brdf - coherent) per steradian, averaged
// over square bins of the lattice about `bin_deg` (in direction cosines, rad) a side; the 5 x 5 lattice directions
// about the specular one, the separable Hann window's main lobe where the coherent part is spread, are left out. A
// bin's standard error is the rms of its directions' over sqrt(max(1, n / 2.25)) for n directions: neighbouring
// lattice directions of a Hann window are correlated over its noise-equivalent bandwidth of 1.5 steps per axis (an
// estimate: against the scatter of the bins between 8 independent maps its median ratio is 1.18 on a smooth and 0.99
// on a rough KC surface, MapValidity.BinStandardErrorMatchesTheScatterBetweenMaps). Energies: the reference's albedo over its lattice (coherent included, theta_o
// <= max_theta_o) and the model's directional albedo over the hemisphere (bsdf/albedo.hpp): a lattice sum would miss
// a peak narrower than the lattice step (the two-scale macro lobe).
// The verdict is validity::decide's; where the reference is outside its own validity (kirchhoff_validity.hpp, on
// the first map) the verdict says so first and is neither conclusive nor trusted.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/bsdf/model_options.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/heightmap/height_map.hpp"
#include "surfscatter/heightmap/outliers.hpp"
#include "surfscatter/validity/kirchhoff_validity.hpp"
#include "surfscatter/validity/validity.hpp"

namespace surfscatter::validity {

struct NamedModel {
    std::string name;  // ghs, ghs_ssa, ggx_stats, two_scale; for a measured map with /measured or /file
    std::shared_ptr<const bsdf::Bsdf> bsdf;
};

struct MapSurface {
    std::vector<heightmap::HeightMap> maps;  // prepared (heightmap/prepare.hpp): the reference's input
    std::vector<NamedModel> models;
    std::vector<std::string> refused;      // "two_scale: <why>": models the factory does not make for this surface
    std::vector<std::string> notes;        // the factory's notes (a measured PSD's range and extrapolation)
    std::string description;               // one line: the file or the statistics and the maps drawn
    // A measured map's outliers (heightmap/outliers.hpp, without the mask): the ones filled with outliers
    // fill, else the ones kept. Kept and dominant, the reference and the models describe them, not the surface.
    heightmap::Outliers outliers;
    heightmap::OutlierPolicy outlier_policy = heightmap::OutlierPolicy::keep;
};

// Error when a measured map's outliers were kept and hold most of its pixel-scale roughness: the Kirchhoff reference
// and the models then describe them, not the surface (front ends call it once their outputs are written).
void require_outliers_not_dominant(const MapSurface& surface);

struct SynthesisSettings {
    double size_um = 0;          // side of the square maps
    std::size_t pixels = 256;    // per side
    std::size_t realizations = 1;
    std::uint64_t seed = 1;
};

// Synthesised maps: at most kMaxSynthesisPixels a side (0.5 GiB of heights a map) and kMaxSynthesisMaps maps, all
// within the available memory (docs/RELIABILITY.md).
inline constexpr long long kMaxSynthesisPixels = 8192, kMaxSynthesisMaps = 1000;
// Throws Error naming `pixels_name` or `realizations_name` (the front end's spelling) for counts outside those bounds
// (pixels at least heightmap::kMinHeightMapSize, at least one map) or maps that do not fit in memory; checked before
// anything is allocated, by map_surface too.
void require_synthesis_counts(long long pixels, long long realizations, const char* pixels_name,
                              const char* realizations_name);

// `surface`: psd measured or file with surface_file (both models' routes are built, the map prepared as
// surface.preparation says), or psd kc / gaussian (then `synthesis` gives the maps). `material` as ModelOptions::material. Throws Error
// for bad input.
MapSurface map_surface(const bsdf::SurfaceOptions& surface, const std::string& material,
                       const SynthesisSettings& synthesis);

struct MapStudy {
    std::vector<double> wavelengths_nm, theta_i_deg, phi_i_deg;
    double subarea_um = 0;        // Kirchhoff sub-area side; 0: a quarter of the maps' shorter side
    double max_theta_o_deg = 80;
    Criteria criteria;
    int threads = 0;
    bool progress = false;        // one bar over cases x maps, with ETA
    // As the caller spells them (criteria, threads, wavelengths); realizations empty for a measured map (one map).
    reference::OptionNames option_names;
};

// Square bins of the lattice (header), in row order; models[m][b] is model m's mean over bin b.
struct LatticeBins {
    std::vector<double> o_x, o_y, theta_o_rad, reference, reference_stderr;
    std::vector<std::vector<double>> models;
};

struct MapCase {
    double wavelength_nm = 0, theta_i_deg = 0, phi_i_deg = 0;
    KirchhoffValidity reference_validity;
    double reference_energy = 0, reference_energy_stderr = 0;
    std::size_t subareas = 0;            // over all maps
    double lattice_step_x = 0, lattice_step_y = 0;
    std::vector<std::string> reference_warnings;
    LatticeBins binned;
    std::vector<ModelResult> models;     // incoherent_per_rad empty: the curves are in `binned`
    Verdict verdict;
};

// The sub-area side the study uses: study.subarea_um, or a quarter of the first map's shorter side.
double map_subarea_um(const MapSurface& surface, const MapStudy& study);
// The study's lists, criteria, threads and sub-area on every map, named by study.option_names: map_validity's first
// step, which a front end calls before it prints the surface's notes (so that a refusal is one line).
void check_map_study(const MapSurface& surface, const MapStudy& study);

// Every (wavelength, theta_i, phi_i), in that nesting order. Stops between cases, or inside one, when
// interrupt_requested(): the cases completed are returned. Throws Error for bad input.
std::vector<MapCase> map_validity(const MapSurface& surface, const material::Conductor& conductor,
                                  const MapStudy& study);

// One row per model and case, the profiles route's columns (polarisation "unpolarised").
std::vector<TableRow> table(const std::vector<MapCase>& cases);

}  // namespace surfscatter::validity
