#include "surfscatter/validity/map_validity.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "surfscatter/bsdf/albedo.hpp"
#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/reference/kirchhoff_map.hpp"
#include "surfscatter/surface/elliptical_statistics.hpp"
#include "surfscatter/heightmap/form.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace surfscatter::validity {

namespace {

constexpr long kSpecularLobeSteps = 2;        // the Hann window's main lobe, each side of the specular direction
constexpr double kHannCellsPerIndependent = 2.25;  // (1.5 steps noise-equivalent bandwidth per axis)^2

const std::vector<bsdf::ModelKind> kModelKinds{bsdf::ModelKind::ghs, bsdf::ModelKind::ghs_ssa, bsdf::ModelKind::ggx,
                                               bsdf::ModelKind::two_scale};

void add_models(MapSurface& out, const bsdf::SurfaceOptions& surface, const std::string& material,
                const std::string& suffix) {
    for (const auto kind : kModelKinds) {
        bsdf::ModelOptions options;
        options.model = kind;
        options.material = material;
        options.surface = surface;
        const std::string name = bsdf::to_string(kind) + suffix;
        try {
            std::vector<std::string> notes;
            std::shared_ptr<const bsdf::Bsdf> model = bsdf::make_bsdf(options, &notes);
            for (const std::string& note : notes) out.notes.push_back(name + ": " + note);
            out.models.push_back({name, std::move(model)});
        } catch (const Error& e) {
            out.refused.push_back(name + ": " + e.what());
        }
    }
}

std::shared_ptr<const surface::RadialStatistics> radial_statistics(const bsdf::SurfaceOptions& s) {
    if (s.psd == bsdf::PsdKind::kc) return std::make_shared<surface::KCorrelation>(s.sigma, s.corr_length, s.gamma);
    return std::make_shared<surface::GaussianAcv>(s.sigma, s.corr_length);
}

std::vector<double> lattice_values(const bsdf::Bsdf& model, const Vec3& wi, double lambda_nm,
                                   const std::vector<double>& o_x, const std::vector<double>& o_y) {
    std::vector<double> f(o_x.size());
    for (std::size_t d = 0; d < o_x.size(); ++d) {
        const Vec3 wo{o_x[d], o_y[d], std::sqrt(std::max(0.0, 1.0 - o_x[d] * o_x[d] - o_y[d] * o_y[d]))};
        f[d] = model.eval(wi, wo, lambda_nm);
    }
    return f;
}

// The maps' Kirchhoff BRDFs averaged on their common lattice; the variances of the means add as independent.
struct MapsReference {
    std::vector<double> o_x, o_y, brdf, coherent, variance;
    double step_x = 0, step_y = 0, albedo = 0, albedo_stderr = 0;
    std::size_t subareas = 0;
    std::vector<std::string> warnings;  // each once
    std::string lobe_unresolved;        // the warning saying a map's sub-areas do not resolve the lobe, if one does
};

// Empty when interrupted.
std::optional<MapsReference> mean_reference(const std::vector<heightmap::HeightMap>& maps,
                                            const material::Conductor& conductor,
                                            const reference::KirchhoffOptions& options, Progress& progress) {
    MapsReference out;
    const double count = static_cast<double>(maps.size());
    double albedo_variance = 0;
    for (const heightmap::HeightMap& map : maps) {
        const reference::KirchhoffResult r = reference::kirchhoff_brdf(map, conductor, options);
        if (r.subareas_done < r.subareas) return std::nullopt;
        if (out.brdf.empty()) {
            out.o_x = r.o_x;
            out.o_y = r.o_y;
            out.step_x = r.step_x;
            out.step_y = r.step_y;
            out.brdf.assign(r.brdf.size(), 0.0);
            out.coherent.assign(r.brdf.size(), 0.0);
            out.variance.assign(r.brdf.size(), 0.0);
        } else if (r.brdf.size() != out.brdf.size() || r.step_x != out.step_x || r.step_y != out.step_y) {
            fail("validity: {} has another direction lattice than the first map (the maps must share their grid)",
                 map.origin());
        }
        for (std::size_t d = 0; d < r.brdf.size(); ++d) {
            out.brdf[d] += r.brdf[d] / count;
            out.coherent[d] += r.coherent[d] / count;
            out.variance[d] += r.standard_error[d] * r.standard_error[d] / (count * count);
        }
        out.albedo += r.albedo / count;
        albedo_variance += r.albedo_standard_error * r.albedo_standard_error / (count * count);
        out.subareas += r.subareas;
        for (const std::string& w : r.warnings)
            if (std::find(out.warnings.begin(), out.warnings.end(), w) == out.warnings.end()) out.warnings.push_back(w);
        if (out.lobe_unresolved.empty()) out.lobe_unresolved = r.lobe_unresolved;
        progress.advance();
    }
    out.albedo_stderr = std::sqrt(albedo_variance);
    return out;
}

// Floor division for lattice indices of either sign.
long bin_index(long m, long cells) { return m >= 0 ? m / cells : -((-m + cells - 1) / cells); }

// Square bins of about `bin_rad` a side in direction cosines (header); the specular lobe left out.
LatticeBins bin_lattice(const MapsReference& reference, const Vec3& wi, const std::vector<std::vector<double>>& model_f,
                        double bin_rad) {
    const long cells_x = std::max(1L, std::lround(bin_rad / reference.step_x));
    const long cells_y = std::max(1L, std::lround(bin_rad / reference.step_y));
    struct Accumulator {
        double ox = 0, oy = 0, ref = 0, var = 0;
        std::vector<double> models;
        std::size_t n = 0;
    };
    std::map<std::pair<long, long>, Accumulator> bins;
    for (std::size_t d = 0; d < reference.brdf.size(); ++d) {
        const long mx = std::lround((reference.o_x[d] + wi.x) / reference.step_x);
        const long my = std::lround((reference.o_y[d] + wi.y) / reference.step_y);
        if (std::abs(mx) <= kSpecularLobeSteps && std::abs(my) <= kSpecularLobeSteps) continue;
        Accumulator& a = bins[{bin_index(my, cells_y), bin_index(mx, cells_x)}];
        if (a.models.empty()) a.models.assign(model_f.size(), 0.0);
        a.ox += reference.o_x[d];
        a.oy += reference.o_y[d];
        a.ref += reference.brdf[d] - reference.coherent[d];
        a.var += reference.variance[d];
        for (std::size_t m = 0; m < model_f.size(); ++m) a.models[m] += model_f[m][d];
        ++a.n;
    }
    LatticeBins b;
    b.models.resize(model_f.size());
    for (const auto& [key, a] : bins) {
        const double n = static_cast<double>(a.n);
        b.o_x.push_back(a.ox / n);
        b.o_y.push_back(a.oy / n);
        b.theta_o_rad.push_back(std::asin(std::min(1.0, std::hypot(a.ox / n, a.oy / n))));
        b.reference.push_back(a.ref / n);
        b.reference_stderr.push_back(std::sqrt(a.var / n / std::max(1.0, n / kHannCellsPerIndependent)));
        for (std::size_t m = 0; m < model_f.size(); ++m) b.models[m].push_back(a.models[m] / n);
    }
    return b;
}

// Why the maps' Kirchhoff BRDF cannot judge the models here, or empty: Kirchhoff outside its validity on the first
// map, or sub-areas too small to resolve the diffuse lobe.
std::string reference_problem(const KirchhoffValidity& validity, const MapsReference& reference) {
    if (!validity.valid) return validity.text;
    return reference.lobe_unresolved;
}

// The models' stated accuracy (relative): GHS's lookup tables (bsdf/ghs.hpp: L1 distance over the lobe below 2e-3);
// the others are closed forms or quadratures stating round-off only.
double stated_accuracy(const std::string& name) {
    return name.rfind("ghs/", 0) == 0 || name == "ghs" ? 2e-3 : 0.0;
}

}  // namespace

void require_outliers_not_dominant(const MapSurface& surface) {
    if (heightmap::kept_and_dominant(surface.outliers, surface.outlier_policy))
        fail("nothing can be trusted: {}: {}: the Kirchhoff reference and the models describe them, not the surface; "
             "outliers fill replaces them by their neighbours' median (docs/HEIGHTMAPS.md \"Outliers\")",
             surface.description, heightmap::describe(surface.outliers));
}

void require_synthesis_counts(long long pixels, long long realizations, const char* pixels_name,
                              const char* realizations_name) {
    const auto min_pixels = static_cast<long long>(heightmap::kMinHeightMapSize);
    if (pixels < min_pixels || pixels > kMaxSynthesisPixels)
        fail("{} must be in [{}, {}], got {}", pixels_name, min_pixels, kMaxSynthesisPixels, pixels);
    if (realizations < 1 || realizations > kMaxSynthesisMaps)
        fail("{} must be in [1, {}] maps, got {}", realizations_name, kMaxSynthesisMaps, realizations);
    // The maps' heights, kept together (8 bytes a pixel), and one synthesis at a time (surface/synthesis.cpp).
    const double pixel_count = static_cast<double>(pixels) * static_cast<double>(pixels);
    require_memory(8.0 * pixel_count * static_cast<double>(realizations) + 48.0 * pixel_count,
                   fmt::format("{} synthesised map(s) of {} x {} pixels", realizations, pixels, pixels));
}

MapSurface map_surface(const bsdf::SurfaceOptions& surface, const std::string& material,
                       const SynthesisSettings& synthesis) {
    MapSurface out;
    if (surface.psd == bsdf::PsdKind::file || surface.psd == bsdf::PsdKind::measured) {
        if (surface.surface_file.empty()) fail("validity: a height map needs its file (surface_file)");
        // Kirchhoff needs heights over an area: a profile file is refused with the line saying what it holds (a map
        // given in memory, whose surface_file is only its name, is already a map). The file is read once.
        bsdf::SurfaceOptions measured = surface;
        if (!surface.height_map && !surface.prepared)
            measured.height_map = std::make_shared<const heightmap::HeightMap>(
                heightmap::read_height_map(surface.surface_file, std::nullopt));
        bsdf::load_height_map(measured);
        out.outlier_policy = surface.preparation.outliers;
        out.outliers = measured.prepared->outliers;
        for (std::string& note : bsdf::preparation_notes(measured)) out.notes.push_back(std::move(note));  // once
        measured.preparation_noted = true;
        out.maps.push_back(measured.prepared->map);
        measured.psd = bsdf::PsdKind::measured;
        add_models(out, measured, material, "/measured");
        measured.psd = bsdf::PsdKind::file;
        add_models(out, measured, material, "/file");
        out.description = fmt::format("{} ({})", heightmap::describe(out.maps.front()),
                                      heightmap::describe(*measured.prepared));
        return out;
    }
    surface::require_surface_length(synthesis.size_um, "map size");
    // Sizes beyond the long long range are beyond the bounds too.
    const auto clamp = [](std::size_t n) { return static_cast<long long>(std::min<std::size_t>(n, 1ULL << 62)); };
    require_synthesis_counts(clamp(synthesis.pixels), clamp(synthesis.realizations), "map pixels", "realizations");
    add_models(out, surface, material, "");
    const auto radial = radial_statistics(surface);
    const surface::SynthesisGrid grid{synthesis.pixels, synthesis.pixels,
                                      synthesis.size_um / static_cast<double>(synthesis.pixels)};
    const bool elliptical = surface.corr_length_v > 0 && surface.corr_length_v != surface.corr_length;
    const auto stretched = elliptical ? std::make_shared<surface::EllipticalStatistics>(
                                            radial, surface.corr_length_v, surface.lay_angle * kDegree)
                                      : nullptr;
    for (std::size_t r = 0; r < synthesis.realizations; ++r) {
        const std::uint64_t seed = synthesis.seed + r;
        out.maps.push_back(stretched ? surface::synthesize_surface(*stretched, grid, seed)
                                     : surface::synthesize_surface(*radial, grid, seed));
    }
    out.description = fmt::format(
        "{}, sigma_h {} um{}, {} map(s) of {} um, {} x {} pixels, seeds from {}", radial->cache_key(), surface.sigma,
        elliptical ? fmt::format(", corr_length_v {} um, lay_angle {} deg", surface.corr_length_v, surface.lay_angle)
                   : std::string(),
        synthesis.realizations, synthesis.size_um, synthesis.pixels, synthesis.pixels, synthesis.seed);
    return out;
}

double map_subarea_um(const MapSurface& surface, const MapStudy& study) {
    const heightmap::HeightMap& first = surface.maps.front();
    return study.subarea_um > 0 ? study.subarea_um : 0.25 * std::min(first.width(), first.height());
}

void check_map_study(const MapSurface& surface, const MapStudy& study) {
    if (surface.maps.empty()) fail("validity: no height map");
    if (surface.models.empty()) fail("validity: the factory makes no model for this surface");
    if (study.wavelengths_nm.empty()) fail("validity: no wavelengths given");
    if (study.theta_i_deg.empty()) fail("validity: no angles of incidence given");
    if (study.phi_i_deg.empty()) fail("validity: no incidence azimuths given");
    for (const double theta : study.theta_i_deg)
        if (!(theta >= 0 && theta < 90)) fail("validity: theta_i must be in [0, 90) degrees, got {}", theta);
    for (const double phi : study.phi_i_deg) require_finite(phi, "phi_i");
    for (const double lambda : study.wavelengths_nm)
        if (!(lambda > 0) || !std::isfinite(lambda)) fail("validity: wavelength must be > 0 nm, got {}", lambda);
    require_valid_criteria(study.criteria, study.option_names);
    require_thread_count(study.threads, study.option_names.threads.c_str());
    require_list_size(study.wavelengths_nm.size(), study.option_names.wavelength.c_str());
    require_list_size(study.theta_i_deg.size(), "theta_i_deg");
    require_list_size(study.phi_i_deg.size(), "phi_i_deg");
    reference::KirchhoffOptions checked;
    checked.subarea_um = map_subarea_um(surface, study);
    checked.option_names = study.option_names;
    for (const heightmap::HeightMap& map : surface.maps) reference::require_kirchhoff_subarea(map, checked);
}

std::vector<MapCase> map_validity(const MapSurface& surface, const material::Conductor& conductor,
                                  const MapStudy& study) {
    check_map_study(surface, study);
    const heightmap::HeightMap& first = surface.maps.front();
    const double subarea = map_subarea_um(surface, study);

    const std::size_t total =
        study.wavelengths_nm.size() * study.theta_i_deg.size() * study.phi_i_deg.size() * surface.maps.size();
    Progress progress("validity", total, study.progress);
    std::vector<MapCase> cases;
    for (const double lambda : study.wavelengths_nm)
        for (const double theta_i : study.theta_i_deg)
            for (const double phi_i : study.phi_i_deg) {
                if (interrupt_requested()) return cases;
                MapCase mc;
                mc.wavelength_nm = lambda;
                mc.theta_i_deg = theta_i;
                mc.phi_i_deg = phi_i;
                mc.reference_validity = kirchhoff_validity(first, lambda, theta_i, phi_i);
                reference::KirchhoffOptions options;
                options.lambda_nm = lambda;
                options.theta_i_rad = theta_i * kDegree;
                options.phi_i_rad = phi_i * kDegree;
                options.subarea_um = subarea;
                options.max_theta_o_rad = study.max_theta_o_deg * kDegree;
                options.threads = study.threads;
                options.option_names = study.option_names;
                const auto reference = mean_reference(surface.maps, conductor, options, progress);
                if (!reference) return cases;  // interrupted
                const MapsReference& sum = *reference;
                mc.reference_energy = sum.albedo;
                mc.reference_energy_stderr = sum.albedo_stderr;
                mc.subareas = sum.subareas;
                mc.lattice_step_x = sum.step_x;
                mc.lattice_step_y = sum.step_y;
                mc.reference_warnings = sum.warnings;

                const Vec3 wi{std::sin(theta_i * kDegree) * std::cos(phi_i * kDegree),
                              std::sin(theta_i * kDegree) * std::sin(phi_i * kDegree), std::cos(theta_i * kDegree)};
                std::vector<std::vector<double>> model_f(surface.models.size());
                for (std::size_t m = 0; m < surface.models.size(); ++m) {
                    const bsdf::Bsdf& model = *surface.models[m].bsdf;
                    ModelResult result;
                    result.model = surface.models[m].name;
                    result.coherent = model.delta_reflectance(wi, lambda);
                    result.own_rel_uncertainty = stated_accuracy(result.model);
                    result.model_energy =
                        bsdf::directional_albedo(model, theta_i * kDegree, lambda, phi_i * kDegree).total();
                    model_f[m] = lattice_values(model, wi, lambda, sum.o_x, sum.o_y);
                    mc.models.push_back(std::move(result));
                }

                mc.binned = bin_lattice(sum, wi, model_f, study.criteria.bin_deg * kDegree);
                const LatticeBins& b = mc.binned;
                for (std::size_t m = 0; m < mc.models.size(); ++m)
                    mc.models[m].comparison = compare_curves(b.theta_o_rad, b.reference, b.reference_stderr,
                                                             b.models[m], study.criteria);
                mc.verdict = decide(mc.models, study.criteria, reference_problem(mc.reference_validity, sum),
                                    study.option_names);
                cases.push_back(std::move(mc));
            }
    progress.finish();
    return cases;
}

std::vector<TableRow> table(const std::vector<MapCase>& cases) {
    std::vector<TableRow> rows;
    for (const MapCase& c : cases)
        for (const ModelResult& m : c.models)
            rows.push_back({m.model, c.wavelength_nm, c.theta_i_deg, "unpolarised", m.comparison, m.model_energy,
                            c.reference_energy, c.verdict.trusted && c.verdict.best_model == m.model, c.verdict.text,
                            c.phi_i_deg, c.reference_validity.valid});
    return rows;
}

}  // namespace surfscatter::validity
