// End-to-end: `surfscatter render` and `surfscatter compare-models` through the binary.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "surfscatter/io/image.hpp"

namespace fs = std::filesystem;
using surfscatter::test::run_cli;

namespace {

fs::path temp_dir() { return surfscatter::test::scratch_directory("surfscatter_test_cli_render"); }

// A small valid scene: a diffuse plane under a point light; $size sets the film size.
const char* kScene = R"(<scene version="3.0.0">
  <default name="size" value="12"/>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, -2, 2" target="0, 0, 0" up="0, 0, 1"/></transform>
    <film type="hdrfilm"><integer name="width" value="$size"/><integer name="height" value="$size"/></film>
    <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
  </sensor>
  <shape type="rectangle"><bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.5, 0.3"/></bsdf></shape>
  <emitter type="point"><point name="position" x="0" y="0" z="1"/>
    <spectrum name="intensity" type="blackbody"><float name="temperature" value="2700"/>
    <float name="scale" value="0.01"/></spectrum></emitter>
</scene>
)";

fs::path write(const std::string& name, const std::string& text) {
    const fs::path path = temp_dir() / name;
    std::ofstream(path) << text;
    return path;
}

}  // namespace

TEST(CliRender, WritesExrAndPngWithDefines) {
    const fs::path scene = write("ok.xml", kScene);
    const fs::path exr = temp_dir() / "ok.exr", png = temp_dir() / "ok.png";
    fs::remove(exr);
    fs::remove(png);
    const auto result = run_cli({"render", scene.string(), "-D", "size=10", "--spp", "2", "--threads", "1", "--seed",
                                 "3", "--quiet", "-o", exr.string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const auto image = surfscatter::io::read_image(exr);
    EXPECT_EQ(image.width, 10);
    EXPECT_EQ(image.height, 10);
    EXPECT_TRUE(fs::exists(png));
    double sum = 0;
    for (float v : image.pixels) sum += v;
    EXPECT_GT(sum, 0.0);
}

TEST(CliRender, BadScenesExitTwoWithFileAndLine) {
    const fs::path unknown = write("unknown.xml", std::string(kScene).replace(std::string(kScene).find("rectangle"), 9, "teapot"));
    auto result = run_cli({"render", unknown.string(), "--quiet", "-o", (temp_dir() / "x.exr").string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find(unknown.string() + ":9: unknown shape plugin 'teapot'"), std::string::npos) << result.err;

    const fs::path syntax = write("syntax.xml", "<scene version=\"3.0.0\">\n  <sensor type=\"perspective\">\n</scene>\n");
    result = run_cli({"render", syntax.string(), "--quiet", "-o", (temp_dir() / "x.exr").string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find(syntax.string() + ":3: XML syntax error"), std::string::npos) << result.err;

    const fs::path texture = write("texture.xml", std::string(kScene).replace(
        std::string(kScene).find("<rgb name=\"reflectance\" value=\"0.7, 0.5, 0.3\"/>"), 47,
        "<texture name=\"reflectance\" type=\"bitmap\"><string name=\"filename\" value=\"missing.png\"/></texture>"));
    result = run_cli({"render", texture.string(), "--quiet", "-o", (temp_dir() / "x.exr").string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find(texture.string() + ":9: file not found"), std::string::npos) << result.err;

    result = run_cli({"render", (temp_dir() / "no_such_scene.xml").string(), "-o", (temp_dir() / "x.exr").string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("scene file not found"), std::string::npos) << result.err;

    result = run_cli({"render", write("ok2.xml", kScene).string(), "-D", "size", "-o", (temp_dir() / "x.exr").string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("-D expects name=value"), std::string::npos) << result.err;

    result = run_cli({"render", write("ok3.xml", kScene).string(), "-o", (temp_dir() / "x.png").string()});
    EXPECT_EQ(result.exit_code, 2);
}

TEST(CliCompareModels, BadOptionsExitTwo) {
    // The full sheet (seven renders with GHS tables) runs in `make demo`; here only the option checking.
    auto result = run_cli({"compare-models", "--view", "4", "-o", (temp_dir() / "cmp").string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("--view must be 1, 2 or 3"), std::string::npos) << result.err;
    result = run_cli({"compare-models", "--scene", (temp_dir() / "absent.xml").string(), "-o", (temp_dir() / "cmp").string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("scene file not found"), std::string::npos) << result.err;
    result = run_cli({"compare-models", "--focus", "0,0", "-o", (temp_dir() / "cmp").string()});
    EXPECT_EQ(result.exit_code, 2);
}

// Issue 36: the demo's sheets show the supplemental's two surfaces (rough: KC sigma 0.15 um, L 4 um, gamma 4; smooth:
// sigma 0.02 um, L 2 um, gamma 3), one sheet per surface and view; -D cannot change what --surfaces sets.
TEST(CliCompareModels, BothSupplementalSurfacesByDefault) {
    // The scene by its path in the checkout: ctest runs this from the build tree, not the repository root.
    const std::string kPhotoSetup = std::string(SURFSCATTER_SOURCE_DIR) + "/scenes/photo-setup/scene.xml";
    const fs::path dir = temp_dir() / "cmp_surfaces";
    fs::remove_all(dir);
    auto result = run_cli({"compare-models", "--scene", kPhotoSetup, "--view", "1", "--list", "-o", dir.string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    for (const char* job : {"sheet/rough/view1", "sheet/smooth/view1", "render/rough/view1/ghs", "render/smooth/view1/ghs"})
        EXPECT_NE(result.out.find(job), std::string::npos) << job << " not in\n" << result.out;
    // The smooth surface's gamma 3 leaves GGX (measured) undefined (its rms slope diverges): left out, with a note.
    EXPECT_EQ(result.out.find("ggx_measured"), std::string::npos) << result.out;
    EXPECT_NE(result.err.find("GGX (measured) left out: a surface has KC gamma 3 <= 3"), std::string::npos) << result.err;
    const std::string study = surfscatter::test::read_whole_file((dir / "study.json").string());
    for (const char* parameter : {"\"sigma\": \"0.15\"", "\"corr_length\": \"4\"", "\"gamma\": \"4\"",
                                  "\"sigma\": \"0.02\"", "\"corr_length\": \"2\"", "\"gamma\": \"3\""})
        EXPECT_NE(study.find(parameter), std::string::npos) << parameter << " not in\n" << study;

    result = run_cli({"compare-models", "--scene", kPhotoSetup, "--surfaces", "smooth", "--view", "1", "--list", "-o", dir.string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find("sheet/smooth/view1"), std::string::npos) << result.out;
    EXPECT_EQ(result.out.find("sheet/rough/view1"), std::string::npos) << result.out;
    result = run_cli({"compare-models", "--scene", kPhotoSetup, "--surfaces", "rough", "--view", "1", "--list", "-o", dir.string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find("render/rough/view1/ggx_measured"), std::string::npos) << result.out;
    EXPECT_EQ(result.err.find("left out"), std::string::npos) << result.err;
    result = run_cli({"compare-models", "--scene", kPhotoSetup, "--surfaces", "scene", "-D", "sigma=0.2", "--view", "1", "--list", "-o",
                      (temp_dir() / "cmp_scene").string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find("sheet/view1"), std::string::npos) << result.out;

    result = run_cli({"compare-models", "--scene", kPhotoSetup, "-D", "sigma=0.2", "-o", dir.string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("-D sigma: --surfaces rough,smooth sets this parameter"), std::string::npos) << result.err;
    result = run_cli({"compare-models", "--scene", kPhotoSetup, "--surfaces", "rough,bumpy", "-o", dir.string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("--surfaces: unknown surface 'bumpy' (rough, smooth or scene)"), std::string::npos) << result.err;
    result = run_cli({"compare-models", "--scene", kPhotoSetup, "--surfaces", "rough,scene", "-o", dir.string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("--surfaces scene cannot be combined"), std::string::npos) << result.err;
}

// Without -o the output is named after the scene, beside it (Mitsuba's rule), and the command says what it wrote.
TEST(CliRender, OutputNamedAfterTheScene) {
    const fs::path scene = write("named_after.xml", kScene);
    const fs::path exr = temp_dir() / "named_after.exr", png = temp_dir() / "named_after.png";
    fs::remove(exr);
    fs::remove(png);
    const auto result = run_cli({"render", scene.string(), "--spp", "1", "--quiet"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_TRUE(fs::exists(exr));
    EXPECT_TRUE(fs::exists(png));
    EXPECT_NE(result.err.find("wrote " + exr.string() + " and " + png.string()), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists("render.exr"));
}

// -D model= takes the models' one vocabulary: an old spelling works with a note, an unknown one lists what works.
TEST(CliRender, ModelDefineListsTheModelsAndTakesOldSpellings) {
    const std::string scene = std::string(SURFSCATTER_SOURCE_DIR) + "/scenes/photo-setup/scene.xml";
    const std::vector<std::string> small = {"-D", "width=8", "-D", "height=6", "--spp", "1", "--quiet", "--threads", "1"};
    auto args = [&](const std::string& model, const fs::path& out) {
        std::vector<std::string> a = {"render", scene, "-D", "model=" + model, "-o", out.string()};
        a.insert(a.end(), small.begin(), small.end());
        return a;
    };
    auto result = run_cli(args("ggx", temp_dir() / "old.exr"));
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.err.find("surfscatter: warning: -D model 'ggx' is an old spelling: write 'ggx_stats'"),
              std::string::npos) << result.err;
    result = run_cli(args("ggx_stats", temp_dir() / "new.exr"));
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(result.err.find("warning"), std::string::npos) << result.err;
    EXPECT_EQ(surfscatter::io::read_image(temp_dir() / "old.exr").pixels,
              surfscatter::io::read_image(temp_dir() / "new.exr").pixels);
    result = run_cli(args("phong", temp_dir() / "x.exr"));
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("model=phong names no file (metal_phong.xml not found): model must be one of conductor | "
                              "ggx_stats | ghs | ghs_ssa | measured | roughconductor | two_scale"),
              std::string::npos) << result.err;
}

// A progress bar only on a terminal: into a pipe or log the render writes its final line alone, no carriage returns.
TEST(CliRender, ProgressIntoAPipeIsOneLine) {
    const fs::path scene = write("progress.xml", kScene);
    const auto result = run_cli({"render", scene.string(), "--spp", "2", "-o", (temp_dir() / "progress.exr").string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(result.err.find('\r'), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("render: started\nrender: 100.0% done in"), std::string::npos) << result.err;
}

// scenes/photo-setup with a height map (issue 33 item 6): -D surface_file alone makes the plate's metal read it (psd
// measured, the preparation's form and outliers passed through) and the render differs from the scene's KC plate; a
// map that is not there is one line naming the file and the scene file's line, and a preparation option without a
// map is an error, exit 2 both.
TEST(CliRender, PhotoSetupRendersAHeightMap) {
    const std::string source = SURFSCATTER_SOURCE_DIR;
    const std::string scene = source + "/scenes/photo-setup/scene.xml", map = source + "/examples/data/kc_surface.gsf";
    const auto args = [&](std::vector<std::string> defines, const fs::path& out) {
        std::vector<std::string> a = {"render", scene, "-D", "model=ggx_stats", "-D", "width=24", "-D", "height=18",
                                      "--spp", "1", "--quiet", "--threads", "1", "-o", out.string()};
        for (const std::string& d : defines) a.insert(a.end(), {"-D", d});
        return a;
    };
    auto result = run_cli(args({"surface_file=" + map, "form=poly2", "outliers=fill"}, temp_dir() / "map.exr"));
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.err.find("surfscatter: render: " + map), std::string::npos) << result.err;  // the map's note
    result = run_cli(args({}, temp_dir() / "kc.exr"));
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(surfscatter::io::read_image(temp_dir() / "map.exr").pixels,
              surfscatter::io::read_image(temp_dir() / "kc.exr").pixels);

    const std::string missing = (temp_dir() / "no_such_map.gsf").string();
    result = run_cli(args({"surface_file=" + missing}, temp_dir() / "x.exr"));
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_EQ(result.err.rfind("surfscatter: error: " + source + "/scenes/photo-setup/surface_map.xml:", 0), 0u) << result.err;
    EXPECT_NE(result.err.find("file not found: " + missing), std::string::npos) << result.err;
    EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << result.err;  // one line

    result = run_cli(args({"form=poly2"}, temp_dir() / "x.exr"));
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("-D form"), std::string::npos) << result.err;
}

// A study whose surface names a height map that is not there: one line naming the study file and key, exit 2, before
// any job runs (the scene's own line is what `render -D surface_file=` reports, above).
TEST(CliStudy, AMissingHeightMapIsOneLineNamingTheStudyKey) {
    const fs::path study = write("map_study.json", R"({"scene": ")" + std::string(SURFSCATTER_SOURCE_DIR) +
                                                       R"(/scenes/photo-setup/scene.xml", "views": [1],
        "models": [{"name": "ggx", "model": "ggx_stats"}], "surfaces": [{"name": "map", "surface_file": "absent.gsf"}],
        "render": {"spp": 1, "width": 8, "height": 6}})");
    const auto result = run_cli({"study", study.string(), "-o", (temp_dir() / "map_study").string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_EQ(result.err, "surfscatter: error: " + study.string() + ": surfaces[0].surface_file: file not found: " +
                              (temp_dir() / "absent.gsf").string() + "\n");
    EXPECT_FALSE(fs::exists(temp_dir() / "map_study" / "manifest.json"));
}
