// Issue 36, class 1 (and class 4's "outputs checked before work"): every command's outputs through one rule
// (core/output_files.hpp), driven through the built CLI. A table of commands x cases: an output equal to an input
// (however spelt: as given, through "..", a symbolic link, a hard link), a derived name equal to an input, two
// outputs equal, an output that is a folder, a device or in a missing folder - each refused before any work with
// one line naming both, exit 2, the input untouched; a name of 255 bytes written; a full disk (`ulimit -f` with
// SIGXFSZ ignored) leaving every old output and no temporary file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace fs = std::filesystem;
using surfscatter::test::CliResult;
using surfscatter::test::read_whole_file;
using surfscatter::test::run_cli;

namespace {

fs::path dir() { return surfscatter::test::scratch_directory("surfscatter_test_cli_outputs"); }

// "@D@" in a case stands for the scratch folder.
std::string expand(std::string text) {
    for (std::size_t at; (at = text.find("@D@")) != std::string::npos;) text.replace(at, 3, dir().string());
    return text;
}

const std::string kMap = std::string(SURFSCATTER_SOURCE_DIR) + "/examples/data/kc_surface.gsf";

// Temporary files (core/output_files.hpp, scripts/plot/plotting.py: ".ss-...") left in `folder`.
std::vector<std::string> temporaries(const fs::path& folder) {
    std::vector<std::string> found;
    for (const auto& entry : fs::directory_iterator(folder))
        if (entry.path().filename().string().rfind(".ss-", 0) == 0) found.push_back(entry.path().filename());
    return found;
}

struct OutputCase {
    std::string name;
    std::vector<std::string> args;  // "@D@" = scratch folder
    std::string message;            // substring of the one stderr line
    std::string untouched;          // a file (an input) whose contents the command must leave as they were
};

void PrintTo(const OutputCase& c, std::ostream* os) { *os << c.name; }

class CliOutputs : public testing::TestWithParam<OutputCase> {
public:
    static void SetUpTestSuite() {
        fs::remove_all(dir());
        fs::create_directories(dir() / "sub");
        fs::create_directories(dir() / "folder.gsf");
        fs::create_directories(dir() / "metals");
        fs::copy_file(kMap, dir() / "map.gsf");
        for (const char* name : {"profile.csv", "scan.csv", "nk.csv", "data.csv", "photo.png", "render.png",
                                 "camera.yml", "metals/metals_reflectance.csv"})
            std::ofstream(dir() / name) << "input " << name << "\n";
        fs::create_hard_link(dir() / "profile.csv", dir() / "profile_hard_link.csv");
        fs::create_symlink(dir() / "map.gsf", dir() / "map_link.gsf");
    }
};

const std::vector<std::string> kExact1d = {"reference", "exact-1d", "--material", "Au", "--wavelength", "500",
                                           "--theta-i", "10", "--polarisation", "s", "--beam-width", "5"};
const std::vector<std::string> kKirchhoff = {"reference", "kirchhoff", "--surface", "@D@/map.gsf", "--material", "Au",
                                             "--wavelength", "500", "--theta-i", "10"};
const std::vector<std::string> kModels1d = {"reference", "models-1d", "--psd", "kc", "--sigma", "0.1", "--corr-length",
                                            "2", "--gamma", "3", "--material", "Au", "--wavelength", "500",
                                            "--theta-i", "10", "--polarisation", "s"};
const std::vector<std::string> kValidityMaps = {"validity", "--map-size-um", "20", "--psd", "kc", "--sigma", "0.05",
                                                "--corr-length", "2", "--gamma", "3", "--wavelengths", "500",
                                                "--theta-i", "10"};
const std::vector<std::string> kSlice = {"brdf", "slice", "--model", "ggx_stats", "--alpha", "0.2", "--material", "Au",
                                         "--wavelength", "550", "--theta-i", "30"};

std::vector<std::string> with(std::vector<std::string> base, const std::vector<std::string>& more) {
    base.insert(base.end(), more.begin(), more.end());
    return base;
}

TEST_P(CliOutputs, RefusedBeforeAnyWorkWithOneLine) {
    const OutputCase& c = GetParam();
    std::vector<std::string> args;
    for (const std::string& a : c.args) args.push_back(expand(a));
    const std::string before = c.untouched.empty() ? "" : read_whole_file(expand(c.untouched));
    const CliResult r = run_cli(args, 60);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line:\n" << r.err;
    EXPECT_NE(r.err.find(expand(c.message)), std::string::npos) << r.err;
    if (!c.untouched.empty()) {
        EXPECT_EQ(read_whole_file(expand(c.untouched)), before);
    }
    EXPECT_EQ(temporaries(dir()), std::vector<std::string>{});
}

INSTANTIATE_TEST_SUITE_P(
    EveryCommand, CliOutputs,
    testing::Values(
        // An output equal to an input.
        OutputCase{"exact1d_output_is_the_profile", with(kExact1d, {"--profile", "@D@/profile.csv", "-o", "@D@/profile.csv"}),
                   "-o @D@/profile.csv would replace the input --profile @D@/profile.csv", "@D@/profile.csv"},
        OutputCase{"exact1d_output_is_a_hard_link_to_the_profile",
                   with(kExact1d, {"--profile", "@D@/profile.csv", "-o", "@D@/profile_hard_link.csv"}),
                   "-o @D@/profile_hard_link.csv would replace the input --profile @D@/profile.csv", "@D@/profile.csv"},
        OutputCase{"kirchhoff_output_is_the_map_spelt_otherwise", with(kKirchhoff, {"-o", "@D@/sub/../map.gsf"}),
                   "-o @D@/sub/../map.gsf would replace the input --surface @D@/map.gsf", "@D@/map.gsf"},
        OutputCase{"kirchhoff_plot_is_the_map", with(kKirchhoff, {"-o", "@D@/k.csv", "--plot", "@D@/map.gsf"}),
                   "--plot @D@/map.gsf would replace the input --surface @D@/map.gsf", "@D@/map.gsf"},
        OutputCase{"fit_csv_is_the_map", {"surface", "fit", "@D@/map.gsf", "--csv", "@D@/map.gsf"},
                   "--csv @D@/map.gsf would replace the input height map @D@/map.gsf", "@D@/map.gsf"},
        OutputCase{"fit_csv_is_a_link_to_the_map", {"surface", "fit", "@D@/map.gsf", "--csv", "@D@/map_link.gsf"},
                   "--csv @D@/map_link.gsf would replace the input height map @D@/map.gsf", "@D@/map.gsf"},
        OutputCase{"compare_sheet_is_the_photo", {"compare", "@D@/photo.png", "@D@/render.png", "-o", "@D@/photo.png"},
                   "-o @D@/photo.png would replace the input photo @D@/photo.png", "@D@/photo.png"},
        OutputCase{"undistort_output_is_the_photo",
                   {"undistort", "@D@/photo.png", "--camera", "@D@/camera.yml", "-o", "@D@/photo.png"},
                   "-o @D@/photo.png would replace the input photo @D@/photo.png", "@D@/photo.png"},
        OutputCase{"pose_output_is_the_camera_file",
                   {"pose", "@D@/photo.png", "--camera", "@D@/camera.yml", "--marker-length", "0.05", "-o",
                    "@D@/camera.yml"},
                   "-o @D@/camera.yml would replace the input --camera @D@/camera.yml", "@D@/camera.yml"},
        OutputCase{"export_output_is_the_map",
                   {"brdf", "export", "--format", "rgl-spectral", "--model", "ghs", "--psd", "measured", "--surface", "@D@/map.gsf", "--material",
                    "Au", "-o", "@D@/map.gsf"},
                   "-o @D@/map.gsf would replace the input --surface @D@/map.gsf", "@D@/map.gsf"},
        // A derived name equal to an input.
        OutputCase{"info_plot_csv_is_the_map", {"surface", "info", "@D@/scan.csv", "--plot", "@D@/scan.png"},
                   "--plot's CSV @D@/scan.csv would replace the input height map @D@/scan.csv", "@D@/scan.csv"},
        OutputCase{"validity_csv_is_the_material", with(kValidityMaps, {"--material", "@D@/nk.csv", "-o", "@D@/nk"}),
                   "-o's CSV @D@/nk.csv would replace the input --material @D@/nk.csv", "@D@/nk.csv"},
        OutputCase{"fit_brdf_csv_is_the_data", {"fit-brdf", "--data", "@D@/data.csv", "--material", "Au", "-o", "@D@/data"},
                   "-o's CSV @D@/data.csv would replace the input --data @D@/data.csv", "@D@/data.csv"},
        OutputCase{"metals_table_is_the_material",
                   {"metals", "--material", "@D@/metals/metals_reflectance.csv", "--out", "@D@/metals"},
                   "--out's reflectance CSV @D@/metals/metals_reflectance.csv would replace the input --material "
                   "@D@/metals/metals_reflectance.csv",
                   "@D@/metals/metals_reflectance.csv"},
        // Two outputs equal.
        OutputCase{"models1d_output_named_png", with(kModels1d, {"-o", "@D@/x.png"}),
                   "the PNG beside -o @D@/x.png and -o @D@/x.png are the same file", ""},
        OutputCase{"slice_csv_is_the_plot", with(kSlice, {"--csv", "@D@/s.png", "--plot", "@D@/s.png"}),
                   "--plot @D@/s.png and --csv @D@/s.png are the same file", ""},
        OutputCase{"selfconv_out_is_the_plots_table",
                   {"selfconv", "--gamma", "3", "--corr-length", "1", "--orders", "5", "--out", "@D@/c_table.csv",
                    "--plot", "@D@/c.png"},
                   "--plot's table CSV @D@/c_table.csv and --out @D@/c_table.csv are the same file", ""},
        // Where an output cannot go: checked before the work (validity's map route used to build every model and
        // print a dozen notes first).
        OutputCase{"validity_missing_folder", with(kValidityMaps, {"--material", "Au", "-o", "@D@/missing/out"}),
                   "cannot write -o's CSV @D@/missing/out.csv: folder @D@/missing does not exist", ""},
        OutputCase{"exact1d_output_is_a_device", with(kExact1d, {"--profile", "@D@/profile.csv", "-o", "/dev/full"}),
                   "-o /dev/full is not a regular file", ""},
        OutputCase{"synth_output_is_a_folder",
                   {"surface", "synth", "--model", "kc", "--sigma", "0.1", "--corr-length", "2", "--gamma", "3",
                    "--size", "64", "--spacing", "0.1", "-o", "@D@/folder.gsf"},
                   "-o @D@/folder.gsf is a folder", ""}),
    [](const testing::TestParamInfo<OutputCase>& param) { return param.param.name; });

// render: every file the scene loads (here a bitmap texture named through -D) is an input its EXR and the PNG
// beside it must not replace; refused after loading the scene, before rendering. (A folder of its own: ctest runs
// CliOutputs' cases, whose setup empties dir(), in parallel with this.)
TEST(CliOutputsRender, FilesTheSceneLoadsAreInputs) {
    const fs::path folder = surfscatter::test::scratch_directory("surfscatter_test_cli_outputs_render");
    const auto scene = [](const std::string& bsdf) {
        return "<scene version=\"3.0.0\">\n"
               "  <sensor type=\"perspective\">\n"
               "    <transform name=\"to_world\"><lookat origin=\"0, -2, 2\" target=\"0, 0, 0\" up=\"0, 0, 1\"/></transform>\n"
               "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/></film>\n"
               "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"2\"/></sampler>\n"
               "  </sensor>\n"
               "  <shape type=\"rectangle\">" + bsdf + "</shape>\n"
               "  <emitter type=\"point\"><point name=\"position\" x=\"0\" y=\"0\" z=\"1\"/><rgb name=\"intensity\" value=\"1\"/></emitter>\n"
               "</scene>\n";
    };
    std::ofstream(folder / "plain.xml") << scene("");
    std::ofstream(folder / "textured.xml")
        << scene("\n    <bsdf type=\"diffuse\"><texture type=\"bitmap\" name=\"reflectance\">\n"
                 "      <string name=\"filename\" value=\"$tex\"/></texture></bsdf>");
    const std::string textured = (folder / "textured.xml").string(), tex_exr = (folder / "tex.exr").string(),
                      tex_png = (folder / "tex.png").string();
    CliResult r = run_cli({"render", (folder / "plain.xml").string(), "-o", tex_exr, "--quiet"}, 60);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string exr = read_whole_file(tex_exr), png = read_whole_file(tex_png);
    // The texture is the EXR itself, then the PNG derived from -o.
    r = run_cli({"render", textured, "-D", "tex=tex.exr", "-o", tex_exr, "--quiet"}, 60);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err, "surfscatter: error: -o " + tex_exr + " would replace the input filename at " + textured + ":9 " +
                         tex_exr + ": name another output\n");
    r = run_cli({"render", textured, "-D", "tex=tex.png", "-o", tex_exr, "--quiet"}, 60);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err, "surfscatter: error: the PNG beside -o " + tex_png + " would replace the input filename at " +
                         textured + ":9 " + tex_png + ": name another output\n");
    EXPECT_EQ(read_whole_file(tex_exr), exr);
    EXPECT_EQ(read_whole_file(tex_png), png);
    // Elsewhere the same scene renders.
    r = run_cli({"render", textured, "-D", "tex=tex.png", "-o", (folder / "out.exr").string(), "--quiet"}, 60);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(temporaries(folder), std::vector<std::string>{});
}

TEST(CliOutputsWritten, NamesOf255BytesAndPrintableNotes) {
    const fs::path folder = dir() / "long";
    fs::remove_all(folder);
    fs::create_directories(folder);
    const std::string stem(251, 'n');
    CliResult r = run_cli(with(kSlice, {"--csv", (folder / (stem + ".csv")).string(), "--plot",
                                        (folder / (stem + ".png")).string()}),
                          120);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_GT(fs::file_size(folder / (stem + ".csv")), 0u);
    EXPECT_GT(fs::file_size(folder / (stem + ".png")), 0u);
    // synth's "wrote" line shows a file name's control characters escaped, as every message does.
    const fs::path odd = folder / "odd\x1b[31m.gsf";
    r = run_cli({"surface", "synth", "--model", "kc", "--sigma", "0.1", "--corr-length", "2", "--gamma", "3", "--size",
                 "64", "--spacing", "0.1", "-o", odd.string()},
                60);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::exists(odd));
    EXPECT_NE(r.err.find("odd\\x1b[31m.gsf"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;
    EXPECT_EQ(temporaries(folder), std::vector<std::string>{});
}

TEST(CliOutputsWritten, AFullDiskLeavesEveryOldOutputAndNoTemporaryFile) {
    const fs::path folder = dir() / "full";
    fs::remove_all(folder);
    fs::create_directories(folder);
    const std::string full = "trap '' XFSZ; ulimit -f 1; ";  // writes beyond 1 KiB fail with EFBIG
    // surface fit --csv: the table is larger than 1 KiB (it was truncated with exit 0).
    std::ofstream(folder / "fit.csv") << "the previous table";
    CliResult r = run_cli({"surface", "fit", kMap, "--csv", (folder / "fit.csv").string()}, 120, full);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("cannot write " + (folder / "fit.csv").string() + ": File too large"), std::string::npos) << r.err;
    EXPECT_EQ(read_whole_file((folder / "fit.csv").string()), "the previous table");
    // board: the PNG and the PDF land together or not at all.
    std::ofstream(folder / "board.png") << "the previous PNG";
    std::ofstream(folder / "board.pdf") << "the previous PDF";
    r = run_cli({"board", "--squares", "10x7", "--square-length", "0.03", "--marker-length", "0.022", "-o",
                 (folder / "board.png").string()},
                120, full);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
    EXPECT_EQ(read_whole_file((folder / "board.png").string()), "the previous PNG");
    EXPECT_EQ(read_whole_file((folder / "board.pdf").string()), "the previous PDF");
    // A plot script's PNG: its CSV (under 8 KiB) and the plot (over) land together or not at all.
    std::ofstream(folder / "info.csv") << "the previous table";
    std::ofstream(folder / "info.png") << "the previous plot";
    r = run_cli({"surface", "info", kMap, "--plot", (folder / "info.png").string()}, 120, "trap '' XFSZ; ulimit -f 16; ");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("psd_fit.py: cannot write " + (folder / "info.png").string() + ": File too large"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(read_whole_file((folder / "info.csv").string()), "the previous table");
    EXPECT_EQ(read_whole_file((folder / "info.png").string()), "the previous plot");
    EXPECT_EQ(temporaries(folder), std::vector<std::string>{});
}

}  // namespace
