// surfscatter surface synth | info | fit: random KC height maps (.gsf, .gwy), statistics of measured height maps
// (any format read_height_map reads), and KC fits.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <sstream>
#include <limits>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "command.hpp"
#include "option_scope.hpp"
#include "preparation_options.hpp"
#include "profile_route.hpp"
#include "statistics_options.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/core/paths.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/elliptical_fit.hpp"
#include "surfscatter/surface/elliptical_statistics.hpp"
#include "surfscatter/surface/height_map_acv.hpp"
#include "surfscatter/heightmap/height_map_fft.hpp"
#include "surfscatter/heightmap/form.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/surface/height_map_slope.hpp"
#include "surfscatter/surface/kc_fit.hpp"
#include "surfscatter/surface/map_statistics.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace surfscatter::cli {

namespace {

struct SynthArgs {
    StatisticsOptions statistics;
    std::optional<double> corr_length_v;  // elliptical statistics (issue 24's convention); LU = --corr-length
    double lay_angle = 0;                 // degrees
    double spacing = 0;
    long long size = 0;
    long long seed = 1;
    std::string output;
    std::string title;
};

// What every command that reads a height map accepts.
struct MapArgs {
    std::string input;
    std::optional<double> spacing, height_unit;
    PreparationArgs preparation;
};

struct InfoArgs : MapArgs {
    std::string plot;
};

// The files `surface info --plot P` writes: P, its CSV and what the preparation plot is drawn from.
struct InfoPlotFiles {
    std::string png, csv, heights, psd_read, psd_prepared, prepared_csv, prepared_png;
    explicit InfoPlotFiles(const std::string& plot) : png(plot) {
        csv = std::filesystem::path(plot).replace_extension(".csv").string();
        const std::string stem = std::filesystem::path(plot).replace_extension().string();
        heights = stem + "_prepared_heights.npy";
        psd_read = stem + "_psd2d_read.npy";
        psd_prepared = stem + "_psd2d_prepared.npy";
        prepared_csv = stem + "_prepared.csv";
        prepared_png = stem + "_prepared.png";
    }
    void declare(OutputFiles& files) const {
        files.output(png, "--plot");
        files.output(csv, "--plot's CSV");
        files.output(heights, "--plot's prepared heights");
        files.output(psd_read, "--plot's 2-D PSD as read");
        files.output(psd_prepared, "--plot's 2-D PSD prepared");
        files.output(prepared_csv, "--plot's preparation CSV");
        files.output(prepared_png, "--plot's preparation plot");
    }
};

struct FitArgs : MapArgs {
    std::optional<double> smoothing;
    std::size_t min_ring = surface::KcFitOptions{}.min_ring;
    double max_zeta_fraction = surface::KcFitOptions{}.max_nyquist_fraction;
    std::string plot, csv;
};

// The files `surface fit --plot P [--csv C]` writes: P, the CSV (C, default P's with .csv), the 2-D PSD beside the
// radial fit, and the elliptical fit's plot with its data.
struct FitPlotFiles {
    std::string png, csv, psd2d, spectrum, elliptical, elliptical_png;
    explicit FitPlotFiles(const FitArgs& args) : png(args.plot), csv(args.csv) {
        if (csv.empty() && !png.empty()) csv = std::filesystem::path(png).replace_extension(".csv").string();
        const std::string stem = std::filesystem::path(png).replace_extension().string();
        psd2d = stem + "_psd2d.npy";
        spectrum = stem + "_spectrum.npy";
        elliptical = stem + "_elliptical.npy";
        elliptical_png = stem + "_elliptical.png";
    }
    void declare(OutputFiles& files, const FitArgs& args) const {
        if (!csv.empty()) files.output(csv, args.csv.empty() ? "--plot's CSV" : "--csv");
        if (png.empty()) return;
        files.output(png, "--plot");
        files.output(psd2d, "--plot's 2-D PSD");
        files.output(spectrum, "--plot's periodogram");
        files.output(elliptical, "--plot's elliptical fit");
        files.output(elliptical_png, "--plot's elliptical plot");
    }
};

void synth(const SynthArgs& args, const CLI::App& cmd) {
    require_applicable_options(cmd, "surface synth",
                               {{"--lay-angle", {"surface synth"}, "--corr-length-v", "the surface is isotropic"}});
    OutputFiles files;
    files.output(args.output, "-o");
    const std::shared_ptr<const surface::RadialStatistics> model = args.statistics.make();
    if (args.seed < 0) fail("--seed must be >= 0, got {}", args.seed);
    heightmap::require_valid_spacing(args.spacing, "--spacing");
    heightmap::require_height_map_extension(args.output, "-o");
    if (args.size < static_cast<long long>(heightmap::kMinHeightMapSize))
        fail("--size must be at least {} samples, got {}", heightmap::kMinHeightMapSize, args.size);
    if (args.corr_length_v) surface::require_surface_length(*args.corr_length_v, "--corr-length-v");
    if (!std::isfinite(args.lay_angle)) fail("--lay-angle must be finite, got {}", args.lay_angle);
    const auto n = static_cast<std::size_t>(args.size);
    const surface::SynthesisGrid grid{n, n, args.spacing};
    const bool anisotropic = args.corr_length_v.has_value();
    heightmap::HeightMap map =
        anisotropic ? surface::synthesize_surface(
                          surface::EllipticalStatistics(model, args.corr_length_v.value_or(model->correlation_length()),
                                                        args.lay_angle * kPi / 180.0),
                          grid, args.seed)
                    : surface::synthesize_surface(*model, grid, args.seed);
    const StatisticsOptions& s = args.statistics;
    map.title = args.title.empty()
                    ? fmt::format("{} sigma_h={} um L_c={} um{}{} seed={}", s.model, s.sigma, s.corr_length,
                                  anisotropic ? fmt::format(" L_v={} um lay_angle={} deg",
                                                            args.corr_length_v.value_or(s.corr_length), args.lay_angle)
                                              : "",
                                  s.gamma ? fmt::format(" gamma={}", *s.gamma) : "", args.seed)
                    : args.title;
    files.write_with(args.output, [&](const std::filesystem::path& tmp) { heightmap::write_height_map(map, tmp); });
    files.commit();
    std::fprintf(stderr, "surfscatter: surface synth: wrote %s (%zu x %zu points of %s um, %s)\n",
                 printable_path(args.output).c_str(), n, n, format_number(args.spacing).c_str(), printable(map.title, kShownPathChars).c_str());
}

void add_map_options(CLI::App* cmd, MapArgs& a) {
    cmd->add_option("map", a.input, "height map: any format Gwyddion reads (.gwy, .gsf, .x3p, .sdf, .dat, .opd, "
                                    "Nanoscope, ...), X3P, Gwyddion text export, or a CSV/whitespace grid")
        ->required();
    cmd->add_option("--spacing", a.spacing, "pixel spacing of a text grid without header (um)");
    cmd->add_option("--height-unit", a.height_unit, "um per height unit of a text grid without header (default 1)");
    add_preparation_options(cmd, a.preparation);
}

// The map prepared (after checking the options): the reader's warnings go to stdout (the `preparation` line once the
// command has its results: a failing command prints its error alone), the outliers to stderr as a note (a warning when kept and holding most of the pixel-scale roughness).
heightmap::PreparedMap read_map(const MapArgs& args, std::optional<heightmap::HeightMap>* as_read = nullptr) {
    if (args.spacing) heightmap::require_valid_spacing(*args.spacing, "--spacing");
    if (args.height_unit) require_positive(*args.height_unit, "--height-unit");
    heightmap::PreparedMap prepared =
        read_prepared_map(args.input, args.spacing, args.height_unit, args.preparation, as_read);
    for (const std::string& warning : prepared.map.source.warnings) std::printf("warning = %s\n", warning.c_str());
    return prepared;
}

void print_value(const char* name, double value) { std::printf("%s = %s\n", name, format_number(value).c_str()); }

void write_measured_plot(const InfoArgs& args, const heightmap::HeightMap& map, OutputFiles& files);

// The rings of a radial PSD as CSV for psd_fit.py: zeta, psd, count, a model's value (column `model_column`), whether
// the ring is in the band used, and its independent samples.
// `extra` columns (a name and one value per ring) follow.
struct RingColumn {
    std::string name;
    std::vector<double> values;
};

std::string ring_csv(const surface::RadialPsd& r, const char* model_column, const std::function<double(double)>& model,
                     const std::function<bool(double)>& in_band, const std::vector<RingColumn>& extra = {}) {
    std::ostringstream out;
    out << "zeta,psd,count," << model_column << ",in_band,independent_samples";
    for (const RingColumn& column : extra) out << ',' << column.name;
    out << '\n';
    for (std::size_t i = 0; i < r.zeta.size(); ++i) {
        out << format_number(r.zeta[i]) << ',' << format_number(r.psd[i]) << ',' << format_number(r.count[i]) << ','
            << format_number(model(r.zeta[i])) << ',' << (in_band(r.zeta[i]) ? 1 : 0) << ','
            << format_number(surface::effective_samples(r.window, r.count[i], r.valid_weight));
        for (const RingColumn& column : extra) out << ',' << format_number(column.values[i]);
        out << '\n';
    }
    return out.str();
}

void write_preparation_plot(const InfoArgs& args, const heightmap::HeightMap& read, const heightmap::PreparedMap& p,
                            OutputFiles& files);

// The profile's 1-D PSD bands as CSV (column `model_column`: `model`; in band: `in_band`; a `profile` column for
// psd_fit.py's 1-D labels) and psd_fit.py's plot of them.
void write_profile_plot(OutputFiles& files, const std::string& plot, const std::string& csv,
                        const surface::RadialPsd& psd, const char* model_column,
                        const std::function<double(double)>& model, const std::function<bool(double)>& in_band,
                        const std::string& title) {
    files.write(csv, ring_csv(psd, model_column, model, in_band, {{"profile", std::vector<double>(psd.zeta.size(), 1.0)}}));
    if (!plot.empty())
        files.write_with(plot, [&](const std::filesystem::path& png) {
            run_plot_script("psd_fit.py", {files.staged(csv).string(), png.string(), title});
        });
    files.commit();
}

// The outputs of a profile's `surface info --plot` or `surface fit [--plot] [--csv]`, checked before the work.
void declare_profile_outputs(OutputFiles& files, const std::string& input, const std::string& plot,
                             const std::string& csv, const char* csv_option) {
    files.input(input, "height map");
    if (!csv.empty()) files.output(csv, csv_option);
    if (!plot.empty()) files.output(plot, "--plot");
}

// The band of a profile's PSD whose mean frequency is `zeta` (its own value: the PSD is its own model column).
std::size_t ring_of(const surface::RadialPsd& psd, double zeta) {
    return static_cast<std::size_t>(std::lower_bound(psd.zeta.begin(), psd.zeta.end(), zeta) - psd.zeta.begin());
}

// `surface info` on a profile: its statistics along its line (no assumption about the area).
void profile_info(const InfoArgs& args, const heightmap::LineScan& scan) {
    const std::string csv =
        args.plot.empty() ? std::string() : std::filesystem::path(args.plot).replace_extension(".csv").string();
    OutputFiles files;
    declare_profile_outputs(files, args.input, args.plot, csv, "--plot's CSV");
    const heightmap::Form form = profile_form(args.preparation);
    const surface::ProfileMoments moments = surface::profile_moments(scan, form);
    std::printf("preparation = %s\n", heightmap::describe_profile(scan, form).c_str());
    std::printf("format = %s\n", scan.source.format.c_str());
    std::printf("reader = %s%s\n", scan.source.reader.c_str(),
                scan.source.channel.empty() ? "" : (", channel " + scan.source.channel).c_str());
    std::printf("kind = profile\npoints = %zu\n", scan.size());
    print_value("dx_um", scan.spacing_um);
    print_value("length_um", scan.length_um());
    print_value("valid_fraction", static_cast<double>(scan.valid_count()) / static_cast<double>(scan.size()));
    print_value("rms_height_um", moments.rms_height_um);
    print_value("rms_slope", moments.rms_slope);
    std::printf("note = statistics along the profile's line; surface fit and brdf treat it as an isotropic surface "
                "(docs/HEIGHTMAPS.md \"Profiles\")\n");
    if (!args.plot.empty()) {
        const surface::RadialPsd psd = surface::estimate_profile_psd(scan, form);
        write_profile_plot(files, args.plot, csv, psd, "model_psd", [&](double z) { return psd.psd[ring_of(psd, z)]; },
                           [](double) { return true; },
                           fmt::format("{}: profile 1-D PSD (Hann, bands of {} frequencies), rms {:.4g} um",
                                       std::filesystem::path(args.input).filename().string(),
                                       surface::kProfileBandBins, moments.rms_height_um));
        std::printf("plot = %s\ncsv = %s\n", printable_path(args.plot).c_str(), printable_path(csv).c_str());
    }
}

void info(const InfoArgs& args) {
    if (const auto scan = read_profile(args.input, args.preparation, args.spacing, args.height_unit))
        return profile_info(args, *scan);
    OutputFiles files;
    files.input(args.input, "height map");
    if (!args.plot.empty()) InfoPlotFiles(args.plot).declare(files);
    std::optional<heightmap::HeightMap> read;
    const heightmap::PreparedMap prepared = read_map(args, args.plot.empty() ? nullptr : &read);
    const heightmap::HeightMap& map = prepared.map;
    const heightmap::HeightMoments moments = heightmap::height_moments(map);
    const surface::AcvMeasures acv = surface::acv_measures(map);
    const auto& source = map.source;
    std::printf("preparation = %s\n", heightmap::describe(prepared).c_str());
    std::printf("format = %s\n", source.format.c_str());
    std::printf("reader = %s%s\n", source.reader.c_str(),
                source.channel.empty() ? "" : (", channel " + source.channel).c_str());
    std::printf("width_px = %zu\nheight_px = %zu\n", map.nx(), map.ny());
    print_value("dx_um", map.spacing_x());
    print_value("dy_um", map.spacing_y());
    print_value("valid_fraction", map.valid_fraction());
    print_value("rms_height_um", moments.rms);
    print_value("rms_slope", surface::rms_slope(map, heightmap::Form::none));
    print_value("skewness", moments.skewness);
    print_value("kurtosis", moments.kurtosis);
    print_value("correlation_length_um", acv.correlation_length_um);
    print_value("texture_aspect_ratio", acv.texture_aspect_ratio);
    if (map.valid_fraction() < heightmap::kMinFitValidFraction)
        std::printf("warning = only %.1f %% of the points are valid; PSD fits need %.0f %%\n",
                    100.0 * map.valid_fraction(), 100.0 * heightmap::kMinFitValidFraction);
    if (acv.correlation_length_um > surface::kMaxCorrelationLengthFraction * std::min(map.width(), map.height()))
        std::printf("warning = correlation_length_um is more than %.0f %% of the map's shorter side: too small a "
                    "patch to measure it (its ACF falls early); measure a larger area\n",
                    100.0 * surface::kMaxCorrelationLengthFraction);
    if (acv.str_is_bound)
        std::printf("warning = along %.1f deg the ACF stays above 0.2 out to the edge of the map: "
                    "texture_aspect_ratio is only an upper bound\n",
                    acv.slowest_direction_deg);
    if (acv.texture_aspect_ratio < 0.5)
        std::printf("warning = texture_aspect_ratio %.3g < 0.5: a directional texture (lay along %.1f deg); the "
                    "isotropic scattering models misrepresent this surface\n",
                    acv.texture_aspect_ratio, acv.slowest_direction_deg);
    if (!args.plot.empty()) {
        write_measured_plot(args, map, files);
        write_preparation_plot(args, *read, prepared, files);
        files.commit();
        const InfoPlotFiles written(args.plot);
        std::printf("plot = %s\ncsv = %s\npreparation_plot = %s\n", printable_path(written.png).c_str(),
                    printable_path(written.csv).c_str(), printable_path(written.prepared_png).c_str());
    }
}

// What `--psd measured` uses (map_statistics.hpp), as name = value lines, a CSV of its rings and the PSD plot.
void write_measured_plot(const InfoArgs& args, const heightmap::HeightMap& map, OutputFiles& files) {
    const surface::MapStatistics stats(map, heightmap::Form::none);
    print_value("measured_sigma_um", stats.sigma_h());
    print_value("measured_sigma_standard_error", stats.sigma_relative_error());
    print_value("measured_band_min_zeta", stats.first_ring());
    print_value("measured_band_max_zeta", stats.nyquist());
    std::printf("measured_window = %s\n", stats.periodic() ? "rectangular (periodic map)" : "hann");
    const InfoPlotFiles out(args.plot);
    files.write(out.csv, ring_csv(stats.rings(), "model_psd", [&](double z) { return stats.psd(z); },
                                  [](double) { return true; }));
    files.write_with(out.png, [&](const std::filesystem::path& png) {
        run_plot_script("psd_fit.py",
                        {files.staged(out.csv).string(), png.string(),
                         fmt::format("{}: PSD that --psd measured uses, band {:.3g}-{:.3g} rad/um, sigma {:.4g} um (+-{:.2g} %)",
                                     std::filesystem::path(args.input).filename().string(), stats.first_ring(),
                                     stats.nyquist(), stats.sigma_h(), 100.0 * stats.sigma_relative_error())});
    });
}

// The elliptical fit's ring means sit on the rings of the fitted (Hann) periodogram: the same lattice.
std::string psd_csv(const surface::SurfaceFit& fit) {
    const surface::KCorrelation model(fit.kc.sigma_h_um, fit.kc.corr_length_um, fit.kc.gamma);
    const surface::RadialPsd elliptical = surface::radial_average(surface::fitted_psd(fit.elliptical, fit.psd));
    return ring_csv(fit.radial, "kc_fit", [&](double z) { return model.psd(z); },
                    [&](double z) { return z >= fit.kc.zeta_min && z <= fit.kc.zeta_max; },
                    {{"elliptical_fit", elliptical.psd}});
}

// `values` (height rows of width) as a little-endian float32 .npy array for a plot script.
std::string npy(const std::vector<double>& values, std::size_t width, std::size_t height) {
    std::string header = fmt::format("{{'descr': '<f4', 'fortran_order': False, 'shape': ({}, {}), }}", height, width);
    header.append(63 - (10 + header.size()) % 64, ' ');
    header += '\n';
    std::string out("\x93NUMPY\x01\x00", 8);
    const auto header_size = static_cast<std::uint16_t>(header.size());
    out += static_cast<char>(header_size & 0xff);
    out += static_cast<char>(header_size >> 8);
    out += header;
    for (double value : values) {
        const auto word = std::bit_cast<std::uint32_t>(static_cast<float>(value));
        for (int shift = 0; shift < 32; shift += 8) out += static_cast<char>((word >> shift) & 0xff);
    }
    return out;
}

// The 2-D PSD over the full zeta-plane, centred (zeta = 0 in the middle), averaged over blocks of
// `block` x `block` frequencies, as a float32 .npy array [row = zeta_y][column = zeta_x] for the plot script.
std::string psd_image(const surface::Psd2d& psd, std::size_t block) {
    const std::size_t width = psd.nx / block, height = psd.ny / block;
    std::vector<double> sums(width * height, 0.0);
    for (std::size_t ky = 0; ky < psd.ny; ++ky)
        for (std::size_t kx = 0; kx < psd.half_nx(); ++kx) {
            const double value = psd.values[ky * psd.half_nx() + kx];
            const long sy = heightmap::signed_frequency_index(ky, psd.ny), sx = static_cast<long>(kx);
            // The point and its Hermitian mirror (-kx, -ky) have the same PSD.
            for (int mirror = 0; mirror < (psd.multiplicity(kx) > 1.0 ? 2 : 1); ++mirror) {
                const long x = (mirror ? -sx : sx) + static_cast<long>(psd.nx / 2);
                const long y = (mirror ? -sy : sy) + static_cast<long>(psd.ny / 2);
                const auto bx = static_cast<std::size_t>(x) / block, by = static_cast<std::size_t>(y) / block;
                if (x >= 0 && y >= 0 && bx < width && by < height) sums[by * width + bx] += value;
            }
        }
    const double norm = 1.0 / static_cast<double>(block * block);
    for (double& sum : sums) sum *= norm;
    return npy(sums, width, height);
}

// The prepared map's heights (um) averaged over blocks of `block` x `block` points (NaN where a block holds no valid
// point), rows = y, as a float32 .npy array.
std::string height_image(const heightmap::HeightMap& map, std::size_t block) {
    const std::size_t width = map.nx() / block, height = map.ny() / block;
    std::vector<double> sums(width * height, 0.0), counts(width * height, 0.0);
    for (std::size_t iy = 0; iy < height * block; ++iy)
        for (std::size_t ix = 0; ix < width * block; ++ix)
            if (map.valid(iy * map.nx() + ix)) {
                sums[(iy / block) * width + ix / block] += map(ix, iy);
                counts[(iy / block) * width + ix / block] += 1.0;
            }
    for (std::size_t i = 0; i < sums.size(); ++i)
        sums[i] = counts[i] > 0 ? sums[i] / counts[i] : std::numeric_limits<double>::quiet_NaN();
    return npy(sums, width, height);
}

// zeta at the outer edge of the image's first column (or row): write_psd_image puts signed index -n/2 there.
double psd_image_edge(std::size_t n, double dzeta) { return -(static_cast<double>(n / 2) + 0.5) * dzeta; }

// What the preparation did (prepared_map.py): the prepared map, the 2-D PSDs as read and prepared, and their rings
// with the waviness's, the band and the nesting indices: <plot>_prepared.png.
void write_preparation_plot(const InfoArgs& args, const heightmap::HeightMap& read, const heightmap::PreparedMap& p,
                            OutputFiles& files) {
    const InfoPlotFiles out(args.plot);
    const std::size_t block = std::max<std::size_t>(1, (std::max(read.nx(), read.ny()) + 255) / 256);
    const surface::Psd2d psd_read = surface::estimate_psd(read, surface::Window::hann, heightmap::Form::none);
    const surface::Psd2d psd_prepared = surface::estimate_psd(p.map, surface::Window::hann, heightmap::Form::none);
    files.write(out.heights, height_image(p.map, block));
    files.write(out.psd_read, psd_image(psd_read, block));
    files.write(out.psd_prepared, psd_image(psd_prepared, block));
    const surface::RadialPsd rings_read = surface::radial_average(psd_read);
    const surface::RadialPsd rings_prepared = surface::radial_average(psd_prepared);
    std::vector<double> waviness(rings_read.zeta.size(), 0.0);
    if (p.waviness) {
        const surface::RadialPsd w =
            surface::radial_average(surface::estimate_psd(*p.waviness, surface::Window::hann, heightmap::Form::none));
        for (std::size_t i = 0; i < std::min(w.psd.size(), waviness.size()); ++i) waviness[i] = w.psd[i];
    }
    std::string rows = "zeta,read,prepared,waviness\n";
    for (std::size_t i = 0; i < std::min(rings_read.zeta.size(), rings_prepared.zeta.size()); ++i)
        rows += fmt::format("{},{},{},{}\n", format_number(rings_read.zeta[i]), format_number(rings_read.psd[i]),
                            format_number(rings_prepared.psd[i]), format_number(waviness[i]));
    files.write(out.prepared_csv, rows);
    const double left = psd_image_edge(read.nx(), psd_read.dzeta_x), bottom = psd_image_edge(read.ny(), psd_read.dzeta_y);
    files.write_with(out.prepared_png, [&](const std::filesystem::path& png) {
        run_plot_script(
            "prepared_map.py",
            {files.staged(out.prepared_csv).string(), files.staged(out.heights).string(), files.staged(out.psd_read).string(),
             files.staged(out.psd_prepared).string(), png.string(),
             fmt::format("{}: {}", std::filesystem::path(args.input).filename().string(), heightmap::describe(p)),
             format_number(p.map.width()), format_number(p.map.height()), format_number(left),
             format_number(left + psd_read.dzeta_x * static_cast<double>(block * (read.nx() / block))), format_number(bottom),
             format_number(bottom + psd_read.dzeta_y * static_cast<double>(block * (read.ny() / block))),
             format_number(p.applied.lambda_s_um), format_number(p.applied.lambda_c_um.value_or(0.0)),
             format_number(surface::nyquist_zeta(p.map))});
    });
}

void write_fit_plot(const FitArgs& args, const heightmap::HeightMap& map, const surface::SurfaceFit& result,
                    OutputFiles& files);

// The elliptical fit under the names of the model options (--corr-length, --corr-length-v, --lay-angle), prefixed,
// and as options to paste; an unresolved one as a warning (the isotropic fit stands).
void print_elliptical(const surface::EllipticalKcFit& e) {
    if (!e.failure.empty()) {
        std::printf("warning = %s\n", e.failure.c_str());
        return;
    }
    print_value("elliptical_sigma_h", e.sigma_h_um);
    print_value("elliptical_sigma_h_error", e.sigma_h_error_um);
    print_value("elliptical_corr_length", e.corr_length_u_um);
    print_value("elliptical_corr_length_error", e.corr_length_u_error_um);
    print_value("elliptical_corr_length_v", e.corr_length_v_um);
    print_value("elliptical_corr_length_v_error", e.corr_length_v_error_um);
    print_value("elliptical_lay_angle", e.lay_angle_deg);
    print_value("elliptical_lay_angle_error", e.lay_angle_error_deg);
    print_value("elliptical_gamma", e.gamma);
    print_value("elliptical_gamma_error", e.gamma_error);
    print_value("elliptical_axis_ratio", e.axis_ratio());
    print_value("elliptical_axis_ratio_error", e.axis_ratio_error);
    print_value("elliptical_log_residual_rms", e.log_residual_rms);
    print_value("elliptical_statistical_floor", e.statistical_floor);
    print_value("elliptical_cells", static_cast<double>(e.cells));
    std::printf("elliptical_window = %s\n", e.window == surface::Window::rectangular ? "rectangular (periodic map)"
                                                                                     : "hann");
    print_value("anisotropy_chi2", e.anisotropy_chi2);
    std::printf("anisotropy = %s\n", e.anisotropic() ? "significant" : "not significant");
    std::printf("elliptical_options = --sigma %s --corr-length %s --corr-length-v %s --lay-angle %s --gamma %s\n",
                format_number(e.sigma_h_um).c_str(), format_number(e.corr_length_u_um).c_str(),
                format_number(e.corr_length_v_um).c_str(), format_number(e.lay_angle_deg).c_str(),
                format_number(e.gamma).c_str());
    if (!e.anisotropic())
        std::printf("warning = the anisotropy is not significant against the periodogram's scatter (LV / LU %.3g +- "
                    "%.2g, chi-square %.3g <= %.3g): the isotropic fit describes this map and the lay angle is "
                    "undetermined\n",
                    e.axis_ratio(), e.axis_ratio_error, e.anisotropy_chi2, surface::kAnisotropyChi2);
    if (e.log_residual_rms > surface::kPoorFitFactor * e.statistical_floor)
        std::printf("warning = the elliptical KC model fits this 2-D PSD poorly (elliptical_log_residual_rms %.3g, %.1f "
                    "times its statistical floor)\n",
                    e.log_residual_rms, e.log_residual_rms / e.statistical_floor);
}

// `surface fit` on a profile: the KC fitted to its 1-D PSD with the KC's profile PSD, under the isotropy note.
void profile_fit(const FitArgs& args, const heightmap::LineScan& scan) {
    if (args.smoothing) fail("--smoothing applies to areal maps; {} is a profile", printable_path(args.input));
    std::string csv = args.csv;
    if (csv.empty() && !args.plot.empty()) csv = std::filesystem::path(args.plot).replace_extension(".csv").string();
    OutputFiles files;
    declare_profile_outputs(files, args.input, args.plot, csv, args.csv.empty() ? "--plot's CSV" : "--csv");
    surface::KcFitOptions options;
    options.form = profile_form(args.preparation);
    options.min_ring = args.min_ring;
    options.max_nyquist_fraction = args.max_zeta_fraction;
    const surface::ProfileFit result = surface::fit_profile(scan, options);
    const surface::KcFit& kc = result.kc;
    const auto write_outputs = [&] {
        if (csv.empty()) return;
        const double variance = kc.sigma_h_um * kc.sigma_h_um;
        const surface::KCorrelation model(kc.sigma_h_um, kc.corr_length_um, kc.gamma);
        write_profile_plot(files, args.plot, csv, result.psd, "kc_fit",
                           [&](double z) { return variance * model.profile_psd_unit(z); },
                           [&](double z) { return z >= kc.zeta_min && z <= kc.zeta_max; },
                           fmt::format("{}: {} to the profile's 1-D PSD, sigma_h {:.4g} um, L_c {:.4g} um, gamma {:.3g}",
                                       std::filesystem::path(args.input).filename().string(),
                                       kc.failure.empty() ? "KC fit" : "NO KC FIT, best attempt", kc.sigma_h_um,
                                       kc.corr_length_um, kc.gamma));
    };
    if (!kc.failure.empty()) {
        write_outputs();
        surface::require_resolved(kc);
    }
    std::printf("preparation = %s\n", heightmap::describe_profile(scan, options.form).c_str());
    std::printf("sigma_h = %s\n", format_number(kc.sigma_h_um).c_str());
    std::printf("corr_length = %s\n", format_number(kc.corr_length_um).c_str());
    std::printf("gamma = %s\n", format_number(kc.gamma).c_str());
    std::printf("rms_slope = %s\n", format_number(result.rms_slope).c_str());
    std::printf("rms_height_profile = %s\n", format_number(result.rms_height_um).c_str());
    std::printf("zeta_min = %s\n", format_number(kc.zeta_min).c_str());
    std::printf("zeta_max = %s\n", format_number(kc.zeta_max).c_str());
    std::printf("log_residual_rms = %s\n", format_number(kc.log_residual_rms).c_str());
    std::printf("statistical_floor = %s\n", format_number(kc.statistical_floor).c_str());
    print_value("fit_band_rms", result.fit_band_rms_um);
    print_value("profile_band_rms", result.profile_band_rms_um);
    std::printf("note = %s\n", surface::kIsotropyNote);
    const double ratio = result.fit_band_rms_um / result.profile_band_rms_um;
    if (!(std::abs(std::log(ratio)) <= std::log1p(surface::kLatticeRmsTolerance)))
        std::printf("warning = the fitted KC holds rms %.4g um on the profile's frequencies, the profile %.4g um (%.0f %% "
                    "apart)\n",
                    result.fit_band_rms_um, result.profile_band_rms_um, 100.0 * std::abs(ratio - 1.0));
    if (kc.log_residual_rms > surface::kPoorFitFactor * kc.statistical_floor)
        std::printf("warning = the KC model fits this profile's PSD poorly (log_residual_rms %.3g, %.1f times its "
                    "statistical floor)\n",
                    kc.log_residual_rms, kc.log_residual_rms / kc.statistical_floor);
    write_outputs();
    if (!csv.empty())
        std::printf("%scsv = %s\n", args.plot.empty() ? "" : ("plot = " + printable_path(args.plot) + "\n").c_str(),
                    printable_path(csv).c_str());
}

void fit(const FitArgs& args) {
    if (const auto scan = read_profile(args.input, args.preparation, args.spacing, args.height_unit))
        return profile_fit(args, *scan);
    OutputFiles files;
    files.input(args.input, "height map");
    const FitPlotFiles out(args);
    out.declare(files, args);
    if (args.smoothing) require_positive(*args.smoothing, "--smoothing");  // before reading the map
    surface::KcFitOptions options;
    const heightmap::PreparedMap prepared = read_map(args);
    const heightmap::HeightMap& map = prepared.map;
    options.form = heightmap::Form::none;  // prepared
    if (args.smoothing) surface::require_smoothing(*args.smoothing, map, "--smoothing");
    options.min_ring = args.min_ring;
    options.max_nyquist_fraction = args.max_zeta_fraction;
    const surface::SurfaceFit result = surface::fit_surface(map, options);
    // An unresolved fit prints nothing on stdout (a failing command's output is its error line alone) but still
    // writes its plot and CSV: a user must see the PSD that did not fit.
    const auto write_outputs = [&] {
        if (!out.csv.empty()) files.write(out.csv, psd_csv(result));
        if (!out.png.empty()) write_fit_plot(args, map, result, files);
        files.commit();
    };
    if (!result.kc.failure.empty()) {
        write_outputs();
        surface::require_resolved(result.kc);
    }
    // A fit whose rms on the map's own frequencies is off by more than kLatticeRmsRefusal is refused (its plot and CSV
    // written), a smaller disagreement beyond the map's scatter is a warning.
    const std::string lattice = surface::lattice_rms_check(result);
    const double lattice_ratio = result.fit_lattice_rms_um / result.map_lattice_rms_um;
    if (!lattice.empty() && (lattice_ratio > surface::kLatticeRmsRefusal || lattice_ratio < 1 / surface::kLatticeRmsRefusal)) {
        write_outputs();
        fail("{}: {}", args.input, lattice);
    }
    std::printf("preparation = %s\n", heightmap::describe(prepared).c_str());
    std::printf("sigma_h = %s\n", format_number(result.kc.sigma_h_um).c_str());
    std::printf("corr_length = %s\n", format_number(result.kc.corr_length_um).c_str());
    std::printf("gamma = %s\n", format_number(result.kc.gamma).c_str());
    std::printf("rms_slope = %s\n", format_number(result.rms_slope).c_str());
    if (args.smoothing)
        std::printf("rms_slope_smoothed = %s\n",
                    format_number(surface::rms_slope_smoothed(map, *args.smoothing, heightmap::Form::none)).c_str());
    std::printf("rms_slope_psd = %s\n", format_number(result.rms_slope_from_psd).c_str());
    std::printf("rms_height_map = %s\n", format_number(result.rms_height_um).c_str());
    std::printf("zeta_min = %s\n", format_number(result.kc.zeta_min).c_str());
    std::printf("zeta_max = %s\n", format_number(result.kc.zeta_max).c_str());
    std::printf("log_residual_rms = %s\n", format_number(result.kc.log_residual_rms).c_str());
    std::printf("statistical_floor = %s\n", format_number(result.kc.statistical_floor).c_str());
    std::printf("texture_aspect_ratio = %s\n", format_number(result.acv.texture_aspect_ratio).c_str());
    std::printf("lay_direction_deg = %s\n", format_number(result.acv.slowest_direction_deg).c_str());
    print_value("valid_fraction", map.valid_fraction());
    print_value("fit_lattice_rms", result.fit_lattice_rms_um);
    print_value("map_lattice_rms", result.map_lattice_rms_um);
    print_elliptical(result.elliptical);
    if (!lattice.empty()) std::printf("warning = %s\n", lattice.c_str());
    if (result.kc.log_residual_rms > surface::kPoorFitFactor * result.kc.statistical_floor)
        std::printf("warning = the KC model fits this PSD poorly (log_residual_rms %.3g, %.1f times its statistical "
                    "floor): use --psd measured for the map's own spectrum\n",
                    result.kc.log_residual_rms, result.kc.log_residual_rms / result.kc.statistical_floor);
    if (result.acv.texture_aspect_ratio < 0.5)
        std::printf("warning = texture aspect ratio Str %.3g%s (lay along %.0f deg): the isotropic KC model "
                    "misrepresents a directional surface\n",
                    result.acv.texture_aspect_ratio, result.acv.str_is_bound ? " (an upper bound)" : "",
                    result.acv.slowest_direction_deg);
    write_outputs();
}

// The 2-D periodogram the elliptical fit used beside the fitted PSD and their ratio: <plot>_elliptical.png.
void write_elliptical_plot(const FitArgs& args, const surface::SurfaceFit& result, std::size_t block, OutputFiles& files) {
    const FitPlotFiles out(args);
    const surface::Psd2d& psd = result.spectrum;
    const surface::EllipticalKcFit& e = result.elliptical;
    files.write(out.spectrum, psd_image(psd, block));
    files.write(out.elliptical, psd_image(surface::fitted_psd(e, psd), block));
    const double left = psd_image_edge(psd.nx, psd.dzeta_x), bottom = psd_image_edge(psd.ny, psd.dzeta_y);
    files.write_with(out.elliptical_png, [&](const std::filesystem::path& png) {
        run_plot_script(
            "psd2d_fit.py",
            {files.staged(out.spectrum).string(), files.staged(out.elliptical).string(), png.string(),
             fmt::format("{}: {}elliptical KC --corr-length {:.4g} --corr-length-v {:.4g} --lay-angle {:.4g} --gamma "
                         "{:.4g} (anisotropy {}), misfit {:.3g} / floor {:.3g}",
                         std::filesystem::path(args.input).filename().string(), e.failure.empty() ? "" : "NO FIT, best attempt: ",
                         e.corr_length_u_um, e.corr_length_v_um, e.lay_angle_deg, e.gamma,
                         e.anisotropic() ? "significant" : "not significant", e.log_residual_rms, e.statistical_floor),
             format_number(left), format_number(left + psd.dzeta_x * static_cast<double>(block * (psd.nx / block))),
             format_number(bottom), format_number(bottom + psd.dzeta_y * static_cast<double>(block * (psd.ny / block))),
             format_number(e.zeta_min), format_number(e.zeta_max), format_number(e.lay_angle_deg)});
    });
    std::printf("elliptical_plot = %s\n", printable_path(out.elliptical_png).c_str());
}

void write_fit_plot(const FitArgs& args, const heightmap::HeightMap& map, const surface::SurfaceFit& result,
                    OutputFiles& files) {
    // The 2-D PSD beside the radial fit: a directional texture shows as a streak through the origin.
    const FitPlotFiles out(args);
    const std::size_t block = std::max<std::size_t>(1, (std::max(map.nx(), map.ny()) + 255) / 256);
    files.write(out.psd2d, psd_image(result.psd, block));
    write_elliptical_plot(args, result, block, files);
    files.write_with(out.png, [&](const std::filesystem::path& png) {
        run_plot_script("psd_fit.py",
                        {files.staged(out.csv).string(), png.string(),
                         fmt::format("{}: {} sigma_h = {:.4g} um, L_c = {:.4g} um, gamma = {:.4g}; band {:.3g}-{:.3g} "
                                     "rad/um",
                                     std::filesystem::path(args.input).filename().string(),
                                     result.kc.failure.empty() ? "KC fit" : "NO KC FIT, best attempt", result.kc.sigma_h_um,
                                     result.kc.corr_length_um, result.kc.gamma, result.kc.zeta_min, result.kc.zeta_max),
                         files.staged(out.psd2d).string(), format_number(psd_image_edge(result.psd.nx, result.psd.dzeta_x)),
                         format_number(psd_image_edge(result.psd.nx, result.psd.dzeta_x) +
                                       result.psd.dzeta_x * static_cast<double>(block * (result.psd.nx / block))),
                         format_number(psd_image_edge(result.psd.ny, result.psd.dzeta_y)),
                         format_number(psd_image_edge(result.psd.ny, result.psd.dzeta_y) +
                                       result.psd.dzeta_y * static_cast<double>(block * (result.psd.ny / block)))});
    });
}

const Command command("surface", [](CLI::App& app) {
    CLI::App* surface_cmd =
        app.add_subcommand("surface", "Height maps: synthesize random surfaces, measured statistics, KC fits");
    surface_cmd->require_subcommand(1);

    auto s = std::make_shared<SynthArgs>();
    CLI::App* synth_cmd = surface_cmd->add_subcommand("synth", "Random Gaussian surface with a KC PSD -> .gsf/.gwy");
    s->statistics.add_to(*synth_cmd);
    synth_cmd->add_option("--size", s->size, "samples per side N (N x N map)")->required();
    synth_cmd->add_option("--spacing", s->spacing, "pixel spacing (um)")->required();
    synth_cmd->add_option("--corr-length-v", s->corr_length_v,
                          "correlation length across the lay (um; default --corr-length: isotropic)");
    synth_cmd->add_option("--lay-angle", s->lay_angle,
                          "lay angle A (deg, from +x towards +y): --corr-length runs along it (docs/SURFACE.md)");
    synth_cmd->add_option("--seed", s->seed, "random seed (same seed, same surface)");
    synth_cmd->add_option("-o,--output", s->output, "output height map (.gsf, or .gwy through Gwyddion)")->required();
    synth_cmd->add_option("--title", s->title, "Title stored in the .gsf header");
    synth_cmd->callback([s, synth_cmd] { synth(*s, *synth_cmd); });

    auto i = std::make_shared<InfoArgs>();
    CLI::App* info_cmd = surface_cmd->add_subcommand(
        "info", "Format, grid, valid fraction, rms, slope, skewness, kurtosis, correlation length and texture "
                "aspect ratio (ISO 25178 Str) of a height map; name = value lines");
    add_map_options(info_cmd, *i);
    info_cmd->add_option("--plot", i->plot,
                         "also write the PSD that --psd measured uses (its ring means, band and standard errors) as "
                         "PNG, with its CSV beside it, and print that route's sigma and band");
    info_cmd->callback([i] { info(*i); });

    auto f = std::make_shared<FitArgs>();
    CLI::App* fit_cmd = surface_cmd->add_subcommand(
        "fit", "Fit KC (sigma_h, L_c, gamma) and elliptical KC (LU, LV, lay angle) to a height map; print name = "
               "value lines");
    add_map_options(fit_cmd, *f);
    fit_cmd->add_option("--smoothing", f->smoothing, "also print the rms slope after Gaussian smoothing (std, um)");
    fit_cmd->add_option("--min-ring", f->min_ring, "lowest PSD ring fitted (default 4)");
    fit_cmd->add_option("--max-zeta-fraction", f->max_zeta_fraction,
                        "highest fitted frequency as a fraction of Nyquist (default 0.5)");
    fit_cmd->add_option("--plot", f->plot,
                        "write the radial PSD with the fit and the 2-D PSD as PNG (CSV and _psd2d.npy beside it), and "
                        "<name>_elliptical.png: the 2-D PSD beside the elliptical fit's and their ratio");
    fit_cmd->add_option("--csv", f->csv, "write the radial PSD and the fit as CSV");
    fit_cmd->callback([f] { fit(*f); });
});

}  // namespace

}  // namespace surfscatter::cli
