// End-to-end: `surfscatter surface synth` and `surfscatter surface fit` through the binary.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <vector>
#include <string>

#include "cli_runner.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace fs = std::filesystem;
namespace ss = surfscatter::surface;
namespace hm = surfscatter::heightmap;
using surfscatter::test::run_cli;

namespace {

fs::path temp_dir() { return surfscatter::test::scratch_directory("surfscatter_test_cli_heightmap"); }

// The numeric "name = value" lines of stdout (format, reader and warning lines hold text).
std::map<std::string, double> parse_values(const surfscatter::test::CliResult& result) {
    std::map<std::string, double> values;
    for (const std::string& line : result.out_lines()) {
        const auto eq = line.find(" = ");
        if (eq == std::string::npos) continue;
        const std::string text = line.substr(eq + 3);
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (!text.empty() && *end == '\0') values[line.substr(0, eq)] = value;
    }
    return values;
}

}  // namespace

TEST(CliHeightmap, SynthThenFitRecoversParameters) {
    const std::string gsf = (temp_dir() / "kc.gsf").string();
    const auto synth = run_cli({"surface", "synth", "--model", "kc", "--sigma", "0.05", "--corr-length", "2",
                                "--gamma", "3", "--size", "1024", "--spacing", "0.5", "--seed", "9", "-o", gsf});
    ASSERT_EQ(synth.exit_code, 0) << synth.err;
    ASSERT_TRUE(fs::exists(gsf));
    EXPECT_EQ(fs::file_size(gsf) % 4, 0u);

    const std::string png = (temp_dir() / "psd.png").string(), csv = (temp_dir() / "psd.csv").string();
    fs::remove(png);
    fs::remove(csv);
    const auto fit = run_cli({"surface", "fit", gsf, "--max-zeta-fraction", "1", "--plot", png, "--csv", csv});
    ASSERT_EQ(fit.exit_code, 0) << fit.err;
    const auto values = parse_values(fit);
    for (const char* name : {"sigma_h", "corr_length", "gamma", "rms_slope"})
        ASSERT_TRUE(values.count(name)) << "missing line '" << name << " = ...' in\n" << fit.out;
    EXPECT_NEAR(values.at("sigma_h") / 0.05, 1.0, 0.05);
    EXPECT_NEAR(values.at("corr_length") / 2.0, 1.0, 0.05);
    EXPECT_NEAR(values.at("gamma") / 3.0, 1.0, 0.05);
    EXPECT_GT(values.at("rms_slope"), 0.0);
    EXPECT_TRUE(fs::exists(png));
    std::ifstream in(csv);
    std::string header;
    std::getline(in, header);
    EXPECT_EQ(header, "zeta,psd,count,kc_fit,in_band,independent_samples,elliptical_fit");
}

// A brushed map (LV / LU = 0.25 at 120 deg) through synth and fit: the elliptical lines, their CSV column, the
// picture, and the isotropic lines unchanged beside them.
TEST(CliHeightmap, EllipticalFitOfABrushedMap) {
    const std::string gsf = (temp_dir() / "brushed.gsf").string();
    const auto synth = run_cli({"surface", "synth", "--sigma", "0.05", "--corr-length", "8", "--corr-length-v", "2",
                                "--lay-angle", "120", "--gamma", "2.5", "--size", "256", "--spacing", "1", "--seed",
                                "6", "-o", gsf});
    ASSERT_EQ(synth.exit_code, 0) << synth.err;
    const std::string png = (temp_dir() / "brushed.png").string(), csv = (temp_dir() / "brushed.csv").string();
    const std::string picture = (temp_dir() / "brushed_elliptical.png").string();
    fs::remove(picture);
    const auto fit = run_cli({"surface", "fit", gsf, "--plot", png, "--csv", csv});
    ASSERT_EQ(fit.exit_code, 0) << fit.err;
    const auto values = parse_values(fit);
    for (const char* name : {"sigma_h", "corr_length", "gamma", "elliptical_corr_length", "elliptical_corr_length_v",
                             "elliptical_lay_angle", "elliptical_gamma", "elliptical_sigma_h",
                             "elliptical_log_residual_rms", "elliptical_statistical_floor", "anisotropy_chi2"})
        ASSERT_TRUE(values.count(name)) << "missing line '" << name << " = ...' in\n" << fit.out;
    EXPECT_LT(std::abs(values.at("elliptical_corr_length") - 8.0), 4.0 * values.at("elliptical_corr_length_error"));
    EXPECT_LT(std::abs(values.at("elliptical_corr_length_v") - 2.0),
              4.0 * values.at("elliptical_corr_length_v_error"));
    EXPECT_LT(std::abs(values.at("elliptical_lay_angle") - 120.0), 4.0 * values.at("elliptical_lay_angle_error"));
    EXPECT_NE(fit.out.find("anisotropy = significant\n"), std::string::npos) << fit.out;
    // The ACF's slowest-decay direction (lay_direction_deg, Str's) is the same lay.
    EXPECT_LT(std::abs(std::remainder(values.at("lay_direction_deg") - values.at("elliptical_lay_angle"), 180.0)), 5.0);
    EXPECT_NE(fit.out.find("elliptical_options = --sigma "), std::string::npos) << fit.out;
    EXPECT_TRUE(fs::exists(picture));
    std::ifstream in(csv);
    std::string header, first;
    std::getline(in, header);
    std::getline(in, first);
    EXPECT_EQ(header, "zeta,psd,count,kc_fit,in_band,independent_samples,elliptical_fit");
    EXPECT_EQ(std::count(first.begin(), first.end(), ','), 6) << first;

    // An isotropic map: the verdict says so.
    const std::string iso = (temp_dir() / "iso.gsf").string();
    ASSERT_EQ(run_cli({"surface", "synth", "--sigma", "0.05", "--corr-length", "4", "--gamma", "2.5", "--size", "256",
                       "--spacing", "1", "--seed", "6", "-o", iso})
                  .exit_code,
              0);
    const auto iso_fit = run_cli({"surface", "fit", iso});
    ASSERT_EQ(iso_fit.exit_code, 0) << iso_fit.err;
    EXPECT_NE(iso_fit.out.find("anisotropy = not significant\n"), std::string::npos) << iso_fit.out;
}

TEST(CliHeightmap, SameSeedSameFile) {
    const std::string a = (temp_dir() / "a.gsf").string(), b = (temp_dir() / "b.gsf").string();
    for (const std::string& out : {a, b})
        ASSERT_EQ(run_cli({"surface", "synth", "--model", "kc", "--sigma", "0.1", "--corr-length", "3", "--gamma",
                           "2.5", "--size", "64", "--spacing", "0.5", "--seed", "3", "-o", out})
                      .exit_code,
                  0);
    EXPECT_EQ(surfscatter::test::read_whole_file(a), surfscatter::test::read_whole_file(b));
}

TEST(CliHeightmap, CsvGridNeedsSpacing) {
    const fs::path csv = temp_dir() / "grid.csv";
    {
        std::ofstream out(csv);
        for (int iy = 0; iy < 64; ++iy)
            for (int ix = 0; ix < 64; ++ix)
                out << 0.01 * std::sin(0.7 * ix + 0.1 * iy * iy) + 0.02 * std::cos(0.31 * ix * iy)
                    << (ix == 63 ? "\n" : ",");
    }
    const auto missing = run_cli({"surface", "fit", csv.string()});
    EXPECT_EQ(missing.exit_code, 2);
    EXPECT_NE(missing.err.find("--spacing"), std::string::npos) << missing.err;
    const auto bad = run_cli({"surface", "fit", csv.string(), "--spacing", "0"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("--spacing"), std::string::npos) << bad.err;
}

TEST(CliHeightmap, BadInputExitsWithStatus2AndOneLine) {
    const fs::path dir = temp_dir();
    const std::string out = (dir / "x.gsf").string();
    struct Case {
        std::initializer_list<std::string> args;
        const char* expected;
    };
    const std::string truncated = (dir / "truncated.gsf").string();
    {
        std::ofstream f(truncated, std::ios::binary);
        f << "Gwyddion Simple Field 1.0\nXRes = 16\nYRes = 16\nXYUnits = m\nZUnits = m\n";
        f.write("\0\0\0", 3);
        f << "only a few bytes";
    }
    const std::string inf_csv = (dir / "inf.csv").string();
    {
        std::ofstream f(inf_csv);
        for (int i = 0; i < 8; ++i) f << (i == 4 ? "1,2,inf,4,5,6,7,8\n" : "1,2,3,4,5,6,7,8\n");
    }
    const std::string garbage = (dir / "garbage.dat").string();
    {
        std::ofstream f(garbage, std::ios::binary);
        for (int i = 0; i < 4000; ++i) f.put(static_cast<char>((i * 37) % 256));
    }
    const std::string broken_zip = (dir / "broken.x3p").string();
    {
        std::ofstream f(broken_zip, std::ios::binary);
        f << "PK\x03\x04 not really a zip archive";
    }
    const std::string photo = (fs::path(SURFSCATTER_SHARED_DATA) / "realdata" / "photos" / "gboriginal.jpg").string();
    const std::string opd = (fs::path(SURFSCATTER_SHARED_DATA) / "realdata" / "heightmaps" / "opd-1.opd").string();
    for (const auto& [args, expected] : std::initializer_list<Case>{
             {{"surface", "synth", "--sigma", "0.1", "--corr-length", "2", "--gamma", "1", "--size", "64",
               "--spacing", "0.5", "-o", out},
              "--gamma"},
             {{"surface", "synth", "--sigma", "0.1", "--corr-length", "2", "--gamma", "0.5", "--size", "64",
               "--spacing", "0.5", "-o", out},
              "--gamma"},
             {{"surface", "synth", "--sigma", "0.1", "--corr-length", "2", "--gamma", "3", "--size", "4",
               "--spacing", "0.5", "-o", out},
              "--size"},
             {{"surface", "synth", "--sigma", "0.1", "--corr-length", "2", "--gamma", "3", "--size", "64",
               "--spacing", "-1", "-o", out},
              "--spacing"},
             {{"surface", "synth", "--sigma", "-0.1", "--corr-length", "2", "--gamma", "3", "--size", "64",
               "--spacing", "1", "-o", out},
              "--sigma"},
             {{"surface", "synth", "--model", "fractal", "--sigma", "0.1", "--corr-length", "2", "--size", "64",
               "--spacing", "1", "-o", out},
              "--model"},
             {{"surface", "synth", "--sigma", "0.1", "--corr-length", "2", "--gamma", "3", "--corr-length-v", "-1", "--size", "64",
               "--spacing", "1", "-o", out},
              "--corr-length-v"},
             {{"surface", "synth", "--sigma", "0.1", "--corr-length", "2", "--gamma", "3", "--lay-angle", "nan", "--size", "64",
               "--spacing", "1", "-o", out},
              "--lay-angle"},
             {{"surface", "fit", truncated}, "truncated"},
             {{"surface", "fit", inf_csv, "--spacing", "1"}, "inf.csv:5: column 3: height is inf"},
             {{"surface", "info", garbage}, "unknown height map format"},
             {{"surface", "info", broken_zip}, "not a readable zip archive"},
             {{"surface", "info", photo}, "no height channel"},
             {{"surface", "info", opd, "--spacing", "0.2"}, "--spacing 0.2 um contradicts the file"},
             {{"surface", "info", opd, "--form", "sphere"}, "--form must be none, plane, poly2"},
             {{"surface", "synth", "--sigma", "0.1", "--corr-length", "2", "--gamma", "3", "--size", "64",
               "--spacing", "1", "-o", (dir / "x.tiff").string()},
              "-o must name a .gsf or .gwy file"},
             {{"surface", "fit", (dir / "missing.gsf").string()}, "height map file not found"},
             {{"surface", "fit"}, "map"},
         }) {
        const auto result = run_cli(args);
        EXPECT_EQ(result.exit_code, 2) << result.err;
        EXPECT_NE(result.err.find(expected), std::string::npos) << result.err;
        EXPECT_EQ(result.out, "");
    }
}

TEST(CliHeightmap, InfoPrintsTheIssuesLinesForARealInstrumentFile) {
    const std::string opd = (fs::path(SURFSCATTER_SHARED_DATA) / "realdata" / "heightmaps" / "opd-1.opd").string();
    const auto result = run_cli({"surface", "info", opd, "--form", "none"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    std::vector<std::string> names;
    for (const std::string& line : result.out_lines()) names.push_back(line.substr(0, line.find(" = ")));
    const std::vector<std::string> expected = {"preparation",  "format",       "reader",        "width_px",    "height_px",
                                               "dx_um",        "dy_um",         "valid_fraction", "rms_height_um",
                                               "rms_slope",    "skewness",      "kurtosis",    "correlation_length_um",
                                               "texture_aspect_ratio"};
    ASSERT_GE(names.size(), expected.size()) << result.out;
    EXPECT_EQ(std::vector<std::string>(names.begin(), names.begin() + 14), expected) << result.out;
    for (std::size_t i = expected.size(); i < names.size(); ++i) EXPECT_EQ(names[i], "warning") << result.out;
    EXPECT_NE(result.out.find("format = Wyko OPD files (.opd)\n"), std::string::npos) << result.out;
    EXPECT_NE(result.out.find("reader = gwyddion 2.62:opdfile, channel 0 'Topography'\n"), std::string::npos)
        << result.out;
    const auto values = parse_values(result);
    EXPECT_EQ(values.at("width_px"), 640);
    EXPECT_EQ(values.at("height_px"), 480);
    EXPECT_NEAR(values.at("dx_um"), 125.909140 / 640, 1e-9);
    EXPECT_NEAR(values.at("valid_fraction"), 1.0 - 116.0 / (640 * 480), 1e-9);  // printed to 10 digits
    EXPECT_NEAR(values.at("rms_height_um"), 8.35645e-3, 0.000005e-3);
    // Str below 0.5 on this file (0.39): the line that says the isotropic models misrepresent it.
    EXPECT_LT(values.at("texture_aspect_ratio"), 0.5);
    EXPECT_NE(result.out.find("warning = texture_aspect_ratio 0.39"), std::string::npos) << result.out;
}

TEST(CliHeightmap, DirectionalTextureWarnsAndIsotropicDoesNot) {
    // Grinding marks along x (a random profile in y, repeated along x, plus 1 % noise) against isotropic KC.
    const fs::path dir = temp_dir();
    const fs::path striped = dir / "striped.csv";
    {
        std::mt19937 engine(3);
        std::normal_distribution<double> normal(0.0, 1.0);
        std::vector<double> profile(128);
        double walk = 0.0;
        for (double& p : profile) p = (walk = 0.7 * walk + normal(engine));
        std::ofstream out(striped);
        for (int iy = 0; iy < 128; ++iy)
            for (int ix = 0; ix < 128; ++ix)
                out << 0.01 * (profile[iy] + 0.01 * normal(engine)) << (ix == 127 ? "\n" : " ");
    }
    // A lay along the rows is what a scanning instrument's row offsets look like (heightmap/rows.hpp): row alignment
    // auto takes it for offsets and would align it away, so this map is read without it.
    const auto lay = run_cli({"surface", "info", striped.string(), "--spacing", "0.5", "--row-alignment", "none"});
    ASSERT_EQ(lay.exit_code, 0) << lay.err;
    EXPECT_LT(parse_values(lay).at("texture_aspect_ratio"), 0.2);
    EXPECT_NE(lay.out.find("the isotropic scattering models misrepresent this surface"), std::string::npos) << lay.out;

    const std::string gwy = (dir / "kc.gwy").string();
    ASSERT_EQ(run_cli({"surface", "synth", "--sigma", "0.05", "--corr-length", "2", "--gamma", "3", "--size", "512",
                       "--spacing", "0.5", "--seed", "2", "-o", gwy})
                  .exit_code,
              0);
    const auto iso = run_cli({"surface", "info", gwy});
    ASSERT_EQ(iso.exit_code, 0) << iso.err;
    EXPECT_GT(parse_values(iso).at("texture_aspect_ratio"), 0.8);
    EXPECT_EQ(iso.out.find("warning"), std::string::npos) << iso.out;
    EXPECT_NE(iso.out.find("reader = gwyddion 2.62:gwyfile"), std::string::npos) << iso.out;
}

TEST(CliHeightmap, FitThroughInvalidPointsAndAFormWithTheTwoDimensionalPsdPlot) {
    // The synthesized KC surface with 10 % invalid points (half at random, half a band) and a bowl 40 sigma deep,
    // written as .gsf (NaN = invalid): --form poly2 recovers the parameters within 5 %.
    const fs::path dir = temp_dir();
    const ss::KCorrelation kc(0.05, 2.0, 3.0);
    const hm::HeightMap surface = ss::synthesize_surface(kc, {1024, 1024, 0.5}, 9);
    std::vector<double> h = surface.heights();
    std::vector<std::uint8_t> valid(h.size(), 1);
    std::mt19937 engine(9);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (std::size_t i = 0; i < h.size(); ++i) {
        const double x = 0.5 * static_cast<double>(i % 1024) - 256, y = 0.5 * static_cast<double>(i / 1024) - 256;
        h[i] += 2.0 * (x * x + 0.6 * y * y + 0.3 * x * y) / (256.0 * 256.0);
        if (uniform(engine) < 0.05 || (i / 1024 >= 300 && i / 1024 < 351)) valid[i] = 0;
    }
    const std::string gsf = (dir / "holes.gsf").string();
    hm::write_gsf(hm::HeightMap(1024, 1024, 0.5, 0.5, h, valid, "holes"), gsf);
    const std::string png = (dir / "holes_psd.png").string();
    fs::remove(png);
    const auto fit = run_cli({"surface", "fit", gsf, "--form", "poly2", "--max-zeta-fraction", "1", "--plot", png});
    ASSERT_EQ(fit.exit_code, 0) << fit.err;
    const auto values = parse_values(fit);
    EXPECT_NEAR(values.at("sigma_h") / 0.05, 1.0, 0.05);
    EXPECT_NEAR(values.at("corr_length") / 2.0, 1.0, 0.05);
    EXPECT_NEAR(values.at("gamma") / 3.0, 1.0, 0.05);
    EXPECT_NEAR(values.at("valid_fraction"), 0.9, 0.005);
    EXPECT_TRUE(fs::exists(png));
    EXPECT_TRUE(fs::exists(dir / "holes_psd_psd2d.npy"));
    EXPECT_TRUE(fs::exists(dir / "holes_psd.csv"));
}

TEST(CliHeightmap, BrdfReadsAnyHeightMapAndReportsItsValidFraction) {
    const std::string opd = (fs::path(SURFSCATTER_SHARED_DATA) / "realdata" / "heightmaps" / "opd-1.opd").string();
    const auto result = run_cli({"brdf", "albedo", "--model", "ggx_stats", "--alpha-from", "measured", "--surface", opd,
                                 "--form", "poly2", "--material", "perfect", "--wavelength", "550", "--theta-i", "20"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.err.find("surfscatter: brdf: " + opd + ": Wyko OPD files (.opd), 640 x 480 points of 0.1967 x "
                              "0.1967 um, 99.96 % valid"),
              std::string::npos)
        << result.err;
    EXPECT_NE(result.out.find("albedo = "), std::string::npos);
}

// Issue 23's acceptance on the real instrument files: each ends in a KC fit or a truthful message (the band and the
// range searched, the advice to use the measured PSD), with its plot written either way, and the measured route
// gives a finite BRDF with its note.
TEST(CliHeightmap, RealFilesFitOrSayWhyWithAPlotAndGiveAFiniteMeasuredBrdf) {
    const fs::path dir = temp_dir();
    for (const char* name : {"metropro-1.dat", "opd-1.opd", "di-1.di"}) {
        const std::string file = (fs::path(SURFSCATTER_SHARED_DATA) / "realdata" / "heightmaps" / name).string();
        const fs::path plot = dir / (std::string(name) + "-fit.png");
        fs::remove(plot);
        const auto fit = run_cli({"surface", "fit", file, "--form", "poly2", "--plot", plot.string()});
        EXPECT_TRUE(fs::exists(plot)) << name << ": " << fit.err;
        const fs::path info_plot = dir / (std::string(name) + "-measured.png");
        const auto info = run_cli({"surface", "info", file, "--form", "poly2", "--plot", info_plot.string()});
        ASSERT_EQ(info.exit_code, 0) << info.err;
        EXPECT_TRUE(fs::exists(info_plot)) << name;
        EXPECT_GT(parse_values(info).at("measured_sigma_standard_error"), 0.0) << info.out;
        if (fit.exit_code == 0) {
            const auto values = parse_values(fit);
            EXPECT_GT(values.at("corr_length"), 0.0) << name;
            EXPECT_GT(values.at("statistical_floor"), 0.0) << name;
        } else {
            EXPECT_EQ(fit.exit_code, 2) << name;
            EXPECT_NE(fit.err.find("was searched from"), std::string::npos) << fit.err;
            EXPECT_NE(fit.err.find("use --psd measured"), std::string::npos) << fit.err;
            EXPECT_EQ(fit.err.find("e+"), std::string::npos) << "no runaway bound: " << fit.err;
        }
        const auto brdf = run_cli({"brdf", "eval", "--model", "ghs", "--psd", "measured", "--surface", file, "--form",
                                   "poly2", "--material", "Au", "--wavelength", "550", "--theta-i", "30", "--theta-o",
                                   "0,29,30.5,45", "--phi-o", "180"});
        ASSERT_EQ(brdf.exit_code, 0) << name << ": " << brdf.err;
        EXPECT_NE(brdf.err.find("note: measured PSD of"), std::string::npos) << brdf.err;
        // The Zygo map's edges are rougher than its centre, which the Hann window weighs (sigma 0.66 of its rms).
        EXPECT_EQ(brdf.err.find("the map is not stationary") != std::string::npos, std::string(name) == "metropro-1.dat")
            << name << ": " << brdf.err;
        double largest = 0.0;
        for (const std::string& line : brdf.out_lines()) {
            if (line.empty() || !std::isdigit(static_cast<unsigned char>(line[0]))) continue;
            const double f = std::stod(line.substr(line.rfind(',') + 1));
            EXPECT_TRUE(std::isfinite(f) && f >= 0.0) << name << ": " << line;
            largest = std::max(largest, f);
        }
        EXPECT_GT(largest, 0.0) << name << ": " << brdf.out;
    }
    // With only a plane removed, the Zygo map's variance sits in its three longest rings (sigma's standard error
    // 45 %): by default the L-filter takes them as waviness (lambda_c 200 um); kept (--lambda-c none), the map is
    // computed, never refused, with a warning naming what to do.
    const std::string zygo = (fs::path(SURFSCATTER_SHARED_DATA) / "realdata" / "heightmaps" / "metropro-1.dat").string();
    const std::vector<std::string> eval = {"brdf", "eval", "--model", "ghs", "--psd", "measured", "--surface", zygo,
                                           "--form", "plane", "--material", "Au", "--wavelength", "550", "--theta-i",
                                           "30", "--theta-o", "30.5", "--phi-o", "180"};
    const auto filtered = run_cli(eval);
    EXPECT_EQ(filtered.exit_code, 0) << filtered.err;
    EXPECT_NE(filtered.err.find("L-filter lambda_c 200 um"), std::string::npos) << filtered.err;
    EXPECT_NE(filtered.err.find("the waviness (periods beyond lambda_c 200 um"), std::string::npos) << filtered.err;
    EXPECT_EQ(filtered.err.find("rests on a few long periods"), std::string::npos) << filtered.err;
    std::vector<std::string> unfiltered = eval;
    unfiltered.insert(unfiltered.end(), {"--lambda-c", "none"});
    const auto kept = run_cli(unfiltered);
    EXPECT_EQ(kept.exit_code, 0) << kept.err;
    EXPECT_NE(kept.err.find("rests on a few long periods"), std::string::npos) << kept.err;
    EXPECT_NE(kept.err.find("--lambda-c"), std::string::npos) << kept.err;
}

// A profile (.hfm, written here from a synthesised KC profile: sigma_h 0.1 um, L_c 5 um, gamma 3, 8192 points 0.5 um
// apart): `surface info` reports it as a profile, `surface fit` fits the KC's profile PSD and prints the isotropy
// note, `brdf` uses the profile's own spectrum by default and the fitted KC with --psd file, with the note on stderr;
// an areal preparation option is an error.
TEST(CliHeightmap, ProfileInfoFitAndBrdf) {
    const std::vector<double> h = ss::synthesize_profile(ss::KCorrelation(0.1, 5.0, 3.0), 8192, 0.5, 3);
    const std::string hfm = (temp_dir() / "profile.hfm").string();
    {
        std::ofstream out(hfm);
        out << "X;Y;valid\n[mm];[mm];[1/0]\n";
        char line[96];
        for (std::size_t i = 0; i < h.size(); ++i) {
            std::snprintf(line, sizeof line, "%.7f;%.10f;1\n", 0.0005 * static_cast<double>(i), h[i] * 1e-3);
            out << line;
        }
    }
    const auto info = run_cli({"surface", "info", hfm});
    ASSERT_EQ(info.exit_code, 0) << info.err;
    EXPECT_NE(info.out.find("kind = profile"), std::string::npos) << info.out;
    EXPECT_EQ(parse_values(info).at("points"), 8192.0);

    const auto fit = run_cli({"surface", "fit", hfm});
    ASSERT_EQ(fit.exit_code, 0) << fit.err;
    const auto values = parse_values(fit);
    EXPECT_NEAR(values.at("sigma_h") / 0.1, 1.0, 0.15) << fit.out;
    EXPECT_NEAR(values.at("gamma"), 3.0, 0.45) << fit.out;
    EXPECT_NE(fit.out.find("note = a profile holds heights along one line: the surface is assumed isotropic"),
              std::string::npos);

    // The profile's own spectrum (--psd measured, a profile's default): each of the four models finite, with the
    // isotropy note and the route's note. (Its accuracy is tested in tests/surface/test_profile_statistics.cpp.)
    const std::vector<std::string> angles = {"--material", "Al", "--wavelength", "550", "--theta-i", "30",
                                             "--theta-o", "20,45", "--phi-o", "180"};
    const auto values_of = [](const surfscatter::test::CliResult& r) {
        std::vector<double> out;
        const auto lines = r.out_lines();
        for (std::size_t i = 1; i < lines.size(); ++i) out.push_back(std::stod(lines[i].substr(lines[i].rfind(',') + 1)));
        return out;
    };
    for (const char* model : {"ghs", "ghs_ssa", "two_scale", "ggx_stats"}) {
        std::vector<std::string> args = {"brdf", "eval", "--model", model, "--surface", hfm};
        args.insert(args.end(), angles.begin(), angles.end());
        const auto brdf = run_cli(args);
        ASSERT_EQ(brdf.exit_code, 0) << brdf.err;
        EXPECT_NE(brdf.err.find("the surface is assumed isotropic"), std::string::npos) << brdf.err;
        EXPECT_NE(brdf.err.find("inverse Abel transform of the profile's Hann-windowed 1-D PSD"), std::string::npos)
            << brdf.err;
        const auto v = values_of(brdf);
        ASSERT_EQ(v.size(), 2u) << brdf.out;
        for (double value : v) EXPECT_TRUE(std::isfinite(value) && value > 0.0) << model << " " << brdf.out;
    }
    // --psd file: the KC fitted to the profile's 1-D PSD, with its note.
    std::vector<std::string> fitted_args = {"brdf", "eval", "--model", "ghs", "--psd", "file", "--surface", hfm};
    fitted_args.insert(fitted_args.end(), angles.begin(), angles.end());
    const auto fitted = run_cli(fitted_args);
    ASSERT_EQ(fitted.exit_code, 0) << fitted.err;
    EXPECT_NE(fitted.err.find("the areal models use KC sigma_h"), std::string::npos) << fitted.err;
    // --measured-spectrum does not apply to a profile (isotropic by assumption).
    std::vector<std::string> ring_args = {"brdf", "eval", "--model", "ghs", "--surface", hfm, "--measured-spectrum", "ring"};
    ring_args.insert(ring_args.end(), angles.begin(), angles.end());
    const auto ring = run_cli(ring_args);
    EXPECT_EQ(ring.exit_code, 2) << ring.err;
    EXPECT_NE(ring.err.find("its 2-D spectrum and its ring average are one"), std::string::npos) << ring.err;

    const auto areal = run_cli({"surface", "info", hfm, "--lambda-c", "100"});
    EXPECT_EQ(areal.exit_code, 2);
    EXPECT_NE(areal.err.find("--lambda-c applies to areal maps; a profile is prepared by its form only"),
              std::string::npos)
        << areal.err;
}
