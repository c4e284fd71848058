// Issue 36, classes 2 and 3 (docs/RELIABILITY.md): an option that does not apply to the chosen mode is an error
// naming it, never ignored or clamped (option_scope.hpp's tables); sizes and counts are bounded before anything is
// allocated (the library's checks, shared with Python). Tables of hostile cases against the built CLI.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace fs = std::filesystem;
using surfscatter::test::run_cli;

namespace {

// One folder per test: ctest runs the tests of this file in parallel, and each checks which outputs exist.
fs::path dir() {
    return surfscatter::test::scratch_directory(std::string("surfscatter_test_cli_options_") +
                                                ::testing::UnitTest::GetInstance()->current_test_info()->name());
}

// A profile CSV of `samples` heights `spacing_um` apart centred on x = 0, alternating 0 and 0.1 um.
std::string profile(const std::string& name, int samples, double spacing_um) {
    const fs::path path = dir() / name;
    std::ofstream out(path);
    out.precision(17);
    out << "x_um,h_um\n";
    for (int i = 0; i < samples; ++i) out << (i - samples / 2) * spacing_um << "," << 0.1 * (i % 2) << "\n";
    return path.string();
}

const std::string kMap = std::string(SURFSCATTER_SOURCE_DIR) + "/examples/data/kc_surface.gsf";

std::vector<std::string> concat(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

struct Case {
    std::string name;
    std::vector<std::string> args;
    std::string message;  // in the one line on stderr
};

// Each case exits 2 with one line naming the option or value, prints nothing on stdout and writes no output.
void expect_refused(const std::vector<Case>& cases) {
    for (const Case& c : cases) {
        const auto r = run_cli(c.args, 120);
        EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.name << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.name << ": " << r.err;
        EXPECT_TRUE(r.out.empty()) << c.name << ": " << r.out;
        EXPECT_EQ(r.err.find("internal error"), std::string::npos) << c.name << ": " << r.err;
    }
}

std::vector<std::string> exact_1d(const std::string& profile_csv, const std::vector<std::string>& extra) {
    return concat({"reference", "exact-1d", "--profile", profile_csv, "--material", "perfect", "--wavelength", "550",
                   "--theta-i", "10", "--polarisation", "s", "--beam-width", "5", "-o", (dir() / "e.csv").string()},
                  extra);
}

std::vector<std::string> random_profiles(const std::vector<std::string>& extra) {
    return concat({"reference", "exact-1d", "--psd", "kc", "--sigma", "0.01", "--corr-length", "1", "--gamma", "3",
                   "--length-um", "30", "--material", "perfect", "--wavelength", "550", "--theta-i", "10",
                   "--polarisation", "s", "--beam-width", "5", "-o", (dir() / "r.csv").string()},
                  extra);
}

std::vector<std::string> validity(const std::vector<std::string>& extra) {
    return concat({"validity", "--material", "perfect", "--wavelengths", "550", "--theta-i", "0", "-o",
                   (dir() / "v").string()},
                  extra);
}

std::vector<std::string> brdf_export(const std::vector<std::string>& extra) {
    return concat({"brdf", "export", "--model", "ghs", "--material", "Au", "--sigma", "0.1", "--corr-length", "2",
                   "--gamma", "3", "--format", "rgl-spectral", "-o", (dir() / "x.bsdf").string()},
                  extra);
}

const std::vector<std::string> kProfilesRoute = {"--psd", "kc", "--sigma", "0.01", "--corr-length", "1", "--gamma", "3",
                                                 "--length-um", "24", "--beam-width", "4", "--realizations", "2"};
const std::vector<std::string> kSynthesised = {"--psd", "kc", "--sigma", "0.01", "--corr-length", "1", "--gamma", "3",
                                               "--map-size-um", "16"};

// Class 2: every option the issue found ignored or clamped, and its kin in the same tables.
TEST(CliOptions, OptionsThatDoNotApplyAreErrors) {
    for (const char* name : {"e.csv", "s.gsf", "b.png"}) fs::remove(dir() / name);  // left by earlier runs
    const std::string flat = profile("flat.csv", 81, 0.5);
    const std::vector<std::string> synth = {"surface", "synth", "--sigma", "0.1", "--corr-length", "2", "--gamma", "3",
                                            "--size", "64", "--spacing", "0.5", "-o", (dir() / "s.gsf").string()};
    const std::vector<std::string> chessboard = {"board", "--board", "chessboard", "--squares", "7x5",
                                                 "--square-length", "0.03", "-o", (dir() / "b.png").string()};
    const std::vector<Case> cases = {
        {"Exact1dProfileSeed", exact_1d(flat, {"--seed", "3"}), "--seed does not apply to one profile (--profile)"},
        {"Exact1dProfileThreads", exact_1d(flat, {"--threads", "100000"}), "--threads does not apply to one profile"},
        {"Exact1dProfileRealizations0", exact_1d(flat, {"--realizations", "0"}),
         "--realizations does not apply to one profile"},
        {"Exact1dProfileSigma", exact_1d(flat, {"--sigma", "0.1"}), "--sigma does not apply to one profile"},
        {"ValidityProfilesForm", validity(concat(kProfilesRoute, {"--form", "bogus"})),
         "--form does not apply to the profiles route (--length-um)"},
        {"ValidityProfilesMaxThetaO", validity(concat(kProfilesRoute, {"--max-theta-o", "nan"})),
         "--max-theta-o does not apply to the profiles route"},
        {"ValidityProfilesMapPixels", validity(concat(kProfilesRoute, {"--map-pixels", "64"})),
         "--map-pixels does not apply to the profiles route"},
        {"ValidityProfilesPhiI", validity(concat(kProfilesRoute, {"--phi-i", "30"})),
         "--phi-i does not apply to the profiles route"},
        {"ValidityFileSigma", validity({"--surface-file", kMap, "--sigma", "0.1"}),
         "--sigma does not apply to a measured map (--surface-file)"},
        {"ValidityFileCorrLength", validity({"--surface-file", kMap, "--corr-length", "2"}),
         "--corr-length does not apply to a measured map"},
        {"ValidityFileGamma", validity({"--surface-file", kMap, "--gamma", "3"}), "--gamma does not apply to a measured map"},
        {"ValidityFileSeed", validity({"--surface-file", kMap, "--seed", "3"}), "--seed does not apply to a measured map"},
        {"ValidityFileMapPixels", validity({"--surface-file", kMap, "--map-pixels", "64"}),
         "--map-pixels does not apply to a measured map"},
        {"ValidityFilePointsPerWavelength", validity({"--surface-file", kMap, "--points-per-wavelength", "10"}),
         "--points-per-wavelength does not apply to a measured map"},
        {"ValidityFileRealizations1", validity({"--surface-file", kMap, "--realizations", "1"}),
         "--realizations does not apply to a measured map"},
        {"ValiditySynthesisedBeamWidth", validity(concat(kSynthesised, {"--beam-width", "4"})),
         "--beam-width does not apply to synthesised maps (--map-size-um)"},
        {"ValidityRealizationsMinus1", validity(concat(kSynthesised, {"--realizations", "-1"})),
         "--realizations must be in [1, 1000] maps, got -1"},
        {"ValidityRealizations0", validity(concat(kSynthesised, {"--realizations", "0"})),
         "--realizations must be in [1, 1000] maps, got 0"},
        {"ValidityLayAngleAlone", validity(concat(kSynthesised, {"--lay-angle", "30"})),
         "--lay-angle needs --corr-length-v: without it the surface is isotropic"},
        {"ValidityLayAngleZeroAlone", validity(concat(kSynthesised, {"--lay-angle", "0"})), "--lay-angle needs --corr-length-v"},
        {"SynthLayAngleAlone", concat(synth, {"--lay-angle", "30"}), "--lay-angle needs --corr-length-v"},
        {"BoardChessboardDictionary", concat(chessboard, {"--dictionary", "6X6_250"}),
         "--dictionary does not apply to --board chessboard: it applies to --board charuco and --board grid"},
        {"BoardChessboardDefaultDictionary", concat(chessboard, {"--dictionary", "4X4_50"}),
         "--dictionary does not apply to --board chessboard"},
        {"BoardGridSquareLength",
         {"board", "--board", "grid", "--markers", "5x7", "--marker-length", "0.03", "--marker-separation", "0.01",
          "--square-length", "0.02", "-o", (dir() / "g.png").string()},
         "--square-length does not apply to --board grid"},
        {"CompareLabelLineBreak",
         {"compare", kMap, kMap, "--labels", "a\nb", "-o", (dir() / "c.png").string()},
         "--labels: item 1 'a\\x0ab' holds a control character"},
    };
    expect_refused(cases);
    EXPECT_FALSE(fs::exists(dir() / "e.csv"));
    EXPECT_FALSE(fs::exists(dir() / "s.gsf"));
    EXPECT_FALSE(fs::exists(dir() / "b.png"));
}

// The same options where they apply are taken (the tables refuse only what is ignored).
TEST(CliOptions, OptionsWhereTheyApplyAreTaken) {
    const auto synth = run_cli({"surface", "synth", "--sigma", "0.1", "--corr-length", "2", "--gamma", "3", "--size",
                                "64", "--spacing", "0.5", "--corr-length-v", "1", "--lay-angle", "30", "-o",
                                (dir() / "lay.gsf").string()});
    EXPECT_EQ(synth.exit_code, 0) << synth.err;
    EXPECT_NE(synth.err.find("L_v=1 um lay_angle=30 deg"), std::string::npos) << synth.err;
    const auto board = run_cli({"board", "--board", "charuco", "--squares", "5x4", "--square-length", "0.03",
                                "--marker-length", "0.02", "--dictionary", "6X6_250", "-o",
                                (dir() / "charuco.png").string()});
    EXPECT_EQ(board.exit_code, 0) << board.err;
    const auto one = run_cli(exact_1d(profile("flat_ok.csv", 81, 0.5), {}));
    EXPECT_EQ(one.exit_code, 0) << one.err;
}

// Class 3: sizes and counts refused, naming them, before anything is allocated (no bad_alloc, no hang, no flat far
// field from a wrapped-around node count).
TEST(CliOptions, WorkIsBoundedBeforeAllocating) {
    const std::vector<Case> cases = {
        {"Exact1dCoarseProfile2p5e299", exact_1d(profile("coarse.csv", 9, 2.5e299), {}),
         "a profile of 9 samples 2.5e+299 um apart needs 3.64e+301 solver nodes at 550 nm"},
        {"Exact1dCoarseProfile1e7", exact_1d(profile("c7.csv", 9, 1e7), {}), "more than 1e+07"},
        {"Exact1dCoarseProfile1e15", exact_1d(profile("c15.csv", 9, 1e15), {}), "more than 1e+07"},
        {"Exact1dTinyWavelength",
         {"reference", "exact-1d", "--profile", profile("flat_w.csv", 81, 0.5), "--material", "perfect",
          "--wavelength", "1e-300", "--theta-i", "10", "--polarisation", "s", "--beam-width", "5", "-o",
          (dir() / "w.csv").string()},
         "solver nodes at 1e-300 nm"},
        {"Exact1dRealizations1e12", random_profiles({"--realizations", "1000000000000"}),
         "--realizations 1000000000000 (a done flag each) needs"},
        {"Exact1dRealizationsInt64Max", random_profiles({"--realizations", "9223372036854775807"}),
         "--realizations 9223372036854775807 (a done flag each) needs"},
        {"ValidityMapPixels1e6", validity(concat(kSynthesised, {"--map-pixels", "1000000"})),
         "--map-pixels must be in [8, 8192], got 1000000"},
        {"ValidityMaps1e6", validity(concat(kSynthesised, {"--realizations", "1000000"})),
         "--realizations must be in [1, 1000] maps, got 1000000"},
        // RGL export: the spectral step and the tables' size before anything is allocated (a step of 1e-300 nm
        // crashed, 512 samples at 256 incidences gave std::bad_alloc, 1e300 nm failed on the temporary file).
        {"BrdfExportLambdaStep1e-300", brdf_export({"--lambda-step", "1e-300"}),
         "--lambda-step must be in [0.1, 640] nm, got 1e-300"},
        {"BrdfExportLambdaStep0p05", brdf_export({"--lambda-step", "0.05"}), "--lambda-step must be in [0.1, 640] nm"},
        {"BrdfExportLambdaStep1e300", brdf_export({"--lambda-step", "1e300"}), "--lambda-step must be in [0.1, 640] nm"},
        {"BrdfExportTablesBeyondMemory",
         brdf_export({"--lambda-step", "0.1", "--sample-resolution", "512", "--theta-i-count", "256"}),
         "available: use a smaller --sample-resolution or --theta-i-count or a larger --lambda-step"},
    };
    expect_refused(cases);
    EXPECT_FALSE(fs::exists(dir() / "x.bsdf"));
}

// Class 4: a message names the option the user gave, not a value derived from it, and says what to do.
TEST(CliOptions, MessagesNameTheOptionGiven) {
    const std::string flat = profile("flat_m.csv", 81, 0.5);
    const fs::path zero = dir() / "zero.csv";
    std::ofstream(zero) << "wavelength_nm,n,k\n400,0,0\n700,0,0\n";
    const auto one_profile = [&](const std::string& material, const std::string& wavelength) {
        return std::vector<std::string>{"reference", "exact-1d", "--profile", flat, "--material", material,
                                        "--wavelength", wavelength, "--theta-i", "10", "--polarisation", "s",
                                        "--beam-width", "5", "-o", (dir() / "e.csv").string()};
    };
    const auto profiles_route = [&](const std::string& material, const std::string& wavelength) {
        return concat({"validity", "--material", material, "--wavelengths", wavelength, "--theta-i", "0", "-o",
                       (dir() / "v").string()},
                      kProfilesRoute);
    };
    const std::vector<Case> cases = {
        {"Exact1dTinyWavelength", one_profile("perfect", "1e-300"),
         "use fewer --points-per-wavelength (now 10), a shorter profile in --profile (now 40 um) or a longer "
         "--wavelength (now 1e-300 nm)"},
        {"Exact1dLongProfiles",
         {"reference", "exact-1d", "--psd", "kc", "--sigma", "0.01", "--corr-length", "1", "--gamma", "3", "--length-um",
          "1e9", "--realizations", "2", "--material", "perfect", "--wavelength", "550", "--theta-i", "10",
          "--polarisation", "s", "--beam-width", "5", "-o", (dir() / "r.csv").string()},
         "a shorter --length-um (now 1e+09 um)"},
        {"Exact1dIndexZero", one_profile(zero.string(), "550"),
         "--material " + zero.string() + ": the refractive index at 550 nm is n = k = 0"},
        {"Exact1dNarrowBeam", one_profile("perfect", "1e300"), "use a wider --beam-width or a shorter --wavelength"},
        {"ValidityTinyWavelength", profiles_route("perfect", "1e-300"),
         "--wavelengths must be between 0.1 and 100000000 nm, got 1e-300"},
        {"ValidityLongProfiles",
         {"validity", "--material", "perfect", "--wavelengths", "550", "--theta-i", "0", "-o", (dir() / "v").string(),
          "--psd", "kc", "--sigma", "0.01", "--corr-length", "1", "--gamma", "3", "--length-um", "1e6", "--beam-width",
          "4", "--realizations", "2"},
         "use fewer --points-per-wavelength (now 10), a shorter --length-um (now 1e+06 um) or a longer --wavelengths "
         "(now 550 nm)"},
        {"ValidityIndexZero", profiles_route(zero.string(), "550"),
         "--material " + zero.string() + ": the refractive index at 550 nm is n = k = 0"},
        {"ValidityFormBogus", validity({"--surface-file", kMap, "--form", "bogus"}),
         "--form must be none, plane, poly2, poly3 or poly4, got 'bogus'"},
        {"ValidityTolerance", validity(concat(kSynthesised, {"--tolerance", "2"})), "--tolerance must be in (0, 1), got 2"},
        {"ValiditySubareaTiny", validity({"--surface-file", kMap, "--subarea-um", "1e-300"}),
         "--subarea-um 1e-300 um is 0 pixels of 0.5 um along x: at least 16 are needed"},
        {"KirchhoffSubareaHuge",
         {"reference", "kirchhoff", "--surface", kMap, "--material", "perfect", "--wavelength", "550", "--theta-i", "10",
          "-o", (dir() / "k.csv").string(), "--subarea-um", "1e300"},
         "--subarea-um 1e+300 um is larger than the map along x"},
        {"ValidityModelsWavelength", profiles_route("perfect", "0.05"),
         "--wavelengths must be between 0.1 and 100000000 nm, got 0.05"},
        {"Models1dTinyWavelength",
         {"reference", "models-1d", "--psd", "kc", "--sigma", "0.1", "--corr-length", "2", "--gamma", "3", "--theta-i",
          "10", "--polarisation", "s", "--material", "perfect", "--wavelength", "1e-300", "-o", (dir() / "m.csv").string()},
         "--wavelength must be between 0.1 and 100000000 nm, got 1e-300"},
    };
    expect_refused(cases);
    EXPECT_FALSE(fs::exists(dir() / "e.csv"));
}

}  // namespace
