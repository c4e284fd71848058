// Study files, their expansion into jobs, the manifest's resume rule, and BRDF jobs run in process. Renders, sheets
// and the MPI runs are exercised end to end in tests/cli/test_cli_distributed.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <unistd.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/io/image.hpp"
#include "surfscatter/render/scene_parameters.hpp"
#include "surfscatter/study/jobs.hpp"
#include "surfscatter/study/manifest.hpp"
#include "surfscatter/study/run_job.hpp"
#include "surfscatter/study/sheet_caption.hpp"
#include "surfscatter/study/study.hpp"

namespace surfscatter::study {
namespace {

namespace fs = std::filesystem;

// One folder per test process (ctest runs the cases in parallel, other worktrees' suites share /tmp), removed at
// exit unless a test failed.
fs::path scratch_root() { return fs::temp_directory_path() / ("surfscatter_test_study_" + std::to_string(::getpid())); }

class ScratchCleanup : public ::testing::Environment {
public:
    void TearDown() override {
        if (::testing::UnitTest::GetInstance()->Passed()) fs::remove_all(scratch_root());
    }
};
const ::testing::Environment* const scratch_cleanup = ::testing::AddGlobalTestEnvironment(new ScratchCleanup);

fs::path scratch(const std::string& name) {
    const fs::path dir = scratch_root() / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

const std::string kScene = std::string(SURFSCATTER_SOURCE_DIR) + "/scenes/photo-setup/scene.xml";

// 2 views x 3 models, one named surface, two lamps, BRDF slices and albedo at two wavelengths.
std::string study_text() {
    return R"({
  "scene": ")" + kScene + R"(",
  "views": [1, 2],
  "parameters": {"material": "Au"},
  "models": [
    {"name": "ggx", "label": "GGX", "model": "ggx_stats", "alpha_from": "measured"},
    {"name": "ghs", "model": "ghs"},
    {"name": "ssa", "label": "SSA GHS", "model": "ghs_ssa"}
  ],
  "surfaces": [{"name": "kc", "sigma": 0.15, "corr_length": 4, "gamma": 3.5}],
  "lamps": [{"name": "warm", "lamp_temperature": 2700}, {"name": "cold", "lamp_temperature": 6500, "lamp_power": 1e-4}],
  "wavelengths": [450, 650.5],
  "render": {"spp": 4, "width": 64, "height": 48, "crop": {"focus": [0.09, 0, 0.001], "radius": 0.06}, "columns": 2},
  "brdf_slices": {"theta_i": [0, 45]},
  "albedo": {"theta_i": [0, 30, 60]}
})";
}

std::string error_of(const std::string& text) {
    try {
        parse_study(text, ".", "s.json");
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

TEST(StudyFile, ReadsEverySection) {
    const Study s = parse_study(study_text(), "/base", "s.json");
    EXPECT_EQ(s.views, (std::vector<std::string>{"1", "2"}));
    ASSERT_EQ(s.models.size(), 3u);
    EXPECT_EQ(s.models[0].label, "GGX");
    EXPECT_EQ(s.models[1].label, "ghs");  // the name when no label is given
    EXPECT_EQ(s.models[1].parameters.at("model"), "ghs");
    EXPECT_EQ(s.surfaces[0].parameters.at("gamma"), "3.5");
    EXPECT_EQ(s.lamps[1].parameters.at("lamp_power"), "0.0001");
    EXPECT_EQ(s.lamps[1].parameters.at("lamp_temperature"), "6500");
    EXPECT_EQ(s.wavelengths, (std::vector<double>{450, 650.5}));
    ASSERT_TRUE(s.render && s.render->crop);
    EXPECT_TRUE(s.render->overview);  // a crop comes with its overview unless told otherwise
    EXPECT_EQ(s.render->columns, 2);
    EXPECT_EQ(s.albedo->theta_i.size(), 3u);
    EXPECT_EQ(s.folder, fs::path("/base"));
}

TEST(StudyFile, ErrorsNameTheFileAndTheEntry) {
    const std::string good = study_text();
    const auto with = [&](const std::string& from, const std::string& to) {
        std::string t = good;
        return t.replace(t.find(from), from.size(), to);
    };
    EXPECT_EQ(error_of(with("\"views\"", "\"veiws\"")).rfind("s.json: unknown key 'veiws'", 0), 0u)
        << error_of(with("\"views\"", "\"veiws\""));
    EXPECT_NE(error_of(with("\"name\": \"ssa\"", "\"name\": \"ghs\"")).find("s.json: models[2].name: 'ghs' is used twice"),
              std::string::npos);
    EXPECT_NE(error_of(with("\"name\": \"kc\"", "\"name\": \"k c\"")).find("surfaces[0].name: name 'k c' may only hold"),
              std::string::npos);
    EXPECT_NE(error_of(with("\"spp\": 4", "\"spp\": 0")).find("render.spp: must be a positive integer"), std::string::npos);
    EXPECT_NE(error_of(with("[0, 45]", "[0, 90]")).find("brdf_slices.theta_i[1]: must be in [0, 90)"), std::string::npos);
    EXPECT_NE(error_of(with("[450, 650.5]", "[450, -1]")).find("wavelengths[1]: must be > 0 nm"), std::string::npos);
    EXPECT_NE(error_of(with("\"radius\": 0.06", "\"radius\": \"big\"")).find("render.crop.radius: must be a number"),
              std::string::npos);
    EXPECT_NE(error_of(with("\"gamma\": 3.5", "\"gamma\": [3]")).find("surfaces[0].gamma: must be a string, number or boolean"),
              std::string::npos);
    EXPECT_NE(error_of(R"({"models": [{"name": "a", "model": "ghs"}]})").find("nothing to do"), std::string::npos);
    EXPECT_NE(error_of(R"({"models": [{"name": "a"}], "render": {}})").find("\"render\" needs \"scene\""), std::string::npos);
    EXPECT_NE(error_of(R"({"models": [{"name": "a"}], "albedo": {"theta_i": [0]}})").find("need \"wavelengths\""),
              std::string::npos);
    EXPECT_NE(error_of("{\"models\": [").find("s.json: not valid JSON"), std::string::npos);
}

TEST(StudyFile, AKeyGivenTwiceIsAnErrorNamingBothLines) {
    const std::string twice = "{\"models\": [{\"name\": \"a\", \"model\": \"ggx\"}],\n\"albedo\": {\"theta_i\": [0],\n"
                              "  \"phi_i\": 0, \"theta_i\": [30]}, \"wavelengths\": [500]}";
    EXPECT_EQ(error_of(twice), "s.json:3: key 'theta_i' is given twice in one object (first at line 2)") << error_of(twice);
    // The same key in different objects (every entry of a list has a "name") is no conflict.
    const std::string apart = "{\"models\": [{\"name\": \"a\", \"model\": \"ggx\", \"alpha\": 0.1},\n"
                              "  {\"name\": \"b\", \"model\": \"ggx\", \"alpha\": 0.2}],\n"
                              " \"albedo\": {\"theta_i\": [0]}, \"wavelengths\": [500]}";
    EXPECT_EQ(parse_study(apart, ".", "s.json").models.size(), 2u);
}

TEST(StudyFile, ANumberBeyondTheDoubleRangeIsNamedWithItsLine) {
    const std::string huge = "{\"models\": [{\"name\": \"a\", \"model\": \"ggx\"}],\n\"wavelengths\": [500, -1e400],\n"
                             "\"albedo\": {\"theta_i\": [0]}}";
    EXPECT_EQ(error_of(huge), "s.json:2: number '-1e400' is beyond the range of a double (+-1.8e308)") << error_of(huge);
}

TEST(StudyFile, WritesWhatItReads) {
    const Study s = parse_study(study_text(), "/base", "s.json");
    const Study again = parse_study(to_json(s), "/elsewhere", "copy.json");
    const std::vector<Job> a = expand(s), b = expand(again);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].id, b[i].id);
        EXPECT_EQ(a[i].outputs, b[i].outputs);
        // The same scene and parameters (the copy names the scene by its absolute path).
        nlohmann::json pa = a[i].parameters, pb = b[i].parameters;
        pa.erase("scene");
        pb.erase("scene");
        EXPECT_EQ(pa, pb) << a[i].id;
    }
}

TEST(StudyJobs, ExpandsViewsModelsSurfacesLampsAndWavelengths) {
    const Study s = parse_study(study_text(), "/base", "s.json");
    const std::vector<Job> jobs = expand(s);
    std::map<std::string, std::size_t> index;
    for (std::size_t i = 0; i < jobs.size(); ++i) {
        EXPECT_TRUE(index.emplace(jobs[i].id, i).second) << "duplicate " << jobs[i].id;
        for (const int d : jobs[i].dependencies) EXPECT_LT(static_cast<std::size_t>(d), i) << jobs[i].id;
    }
    std::map<JobKind, int> count;
    for (const Job& j : jobs) ++count[j.kind];
    // 3 tables (one per model: each has renders and BRDF jobs), 2 lamps x 2 views x 3 models renders, 4 overviews,
    // 4 sheets, 2 wavelengths x 3 models slices and albedo, 2 + 2 plots.
    EXPECT_EQ(count[JobKind::tables], 3);
    EXPECT_EQ(count[JobKind::render], 12);
    EXPECT_EQ(count[JobKind::overview], 4);
    EXPECT_EQ(count[JobKind::sheet], 4);
    EXPECT_EQ(count[JobKind::slice], 6);
    EXPECT_EQ(count[JobKind::albedo], 6);
    EXPECT_EQ(count[JobKind::slice_plot], 2);
    EXPECT_EQ(count[JobKind::albedo_plot], 2);

    const Job& render = jobs.at(index.at("render/kc/cold/view2/ssa"));
    EXPECT_EQ(render.outputs, (std::vector<std::string>{"renders/kc/cold/view2/ssa.exr", "renders/kc/cold/view2/ssa.png"}));
    using Text = std::map<std::string, std::string>;
    const auto defines = render.parameters["defines"].get<Text>();
    const std::map<std::string, std::string> expected = {
        {"view", "2"},     {"width", "64"},   {"height", "48"},  {"material", "Au"},           {"model", "ghs_ssa"},
        {"sigma", "0.15"}, {"corr_length", "4"}, {"gamma", "3.5"}, {"lamp_temperature", "6500"}, {"lamp_power", "0.0001"}};
    EXPECT_EQ(defines, expected);
    EXPECT_EQ(render.parameters["spp"], 4);
    EXPECT_EQ(jobs.at(static_cast<std::size_t>(render.dependencies.at(0))).id, "tables/kc/ssa");

    // The BRDF jobs see the model parameters only (no lamp, no view).
    const Job& slice = jobs.at(index.at("slice/kc/650.5nm/ggx"));
    const std::map<std::string, std::string> model_options = {{"material", "Au"}, {"model", "ggx_stats"},
                                                              {"alpha_from", "measured"}, {"sigma", "0.15"},
                                                              {"corr_length", "4"}, {"gamma", "3.5"}};
    EXPECT_EQ(slice.parameters["model_options"].get<Text>(), model_options);
    EXPECT_EQ(slice.outputs, (std::vector<std::string>{"brdf/kc/slice_650.5nm_ggx.csv"}));

    // The sheet: models in order, the overview opening the second row (2 columns), after everything it shows.
    const Job& sheet = jobs.at(index.at("sheet/kc/warm/view1"));
    EXPECT_EQ(sheet.outputs, (std::vector<std::string>{"sheets/kc_warm_view1.png"}));
    EXPECT_EQ(sheet.inputs, (std::vector<std::string>{"renders/kc/warm/view1/ggx.png", "renders/kc/warm/view1/ghs.png",
                                                       "renders/kc/warm/view1/overview.png", "renders/kc/warm/view1/ssa.png"}));
    EXPECT_EQ(sheet.parameters["panels"][2][0], "whole view");
    EXPECT_EQ(sheet.parameters["title"], "photo-setup view 1, kc, warm, 4 spp");
    std::set<std::string> shown;
    for (const int d : sheet.dependencies) shown.insert(jobs.at(static_cast<std::size_t>(d)).id);
    EXPECT_EQ(shown, (std::set<std::string>{"render/kc/warm/view1/ggx", "render/kc/warm/view1/ghs",
                                            "render/kc/warm/view1/ssa", "overview/kc/warm/view1"}));
    // Captions: label, surface and g0 (sigma 0.15 um at 550 nm: (4 pi 0.15 / 0.55)^2 = 11.7), SSA's warning.
    EXPECT_EQ(sheet.parameters["panels"][0][0], "GGX\nsigma 0.15 um, g0 11.7 at 550 nm");
    EXPECT_EQ(sheet.parameters["panels"][3][0],
              "SSA GHS\nsigma 0.15 um, g0 11.7 at 550 nm\n!SSA outside its validity (g0 11.7 > 1): far too sharp");
    EXPECT_EQ(sheet.parameters["crop_to_difference"], false);  // the study crops its renders itself
    // Plots name the models by their labels.
    const Job& plot = jobs.at(index.at("slice-plot/kc/450nm"));
    EXPECT_EQ(plot.parameters["labels"], (nlohmann::json{{"ggx", "GGX"}, {"ghs", "ghs"}, {"ssa", "SSA GHS"}}));
}

// Issue 36, class 1: a job's outputs never replace a file the study loads or another job's output
// (core/output_files.hpp's rule), refused when the study is expanded, before any job runs.
TEST(StudyJobs, OutputsThatWouldReplaceAnInputOrEachOtherAreRefused) {
    const auto expand_error = [](const Study& s) {
        try {
            expand(s);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    // A model named "overview" renders onto the view's overview image.
    std::string text = study_text();
    text.replace(text.find(R"("name": "ghs")"), 13, R"("name": "overview")");
    const std::string both = expand_error(parse_study(text, "/base", "s.json"));
    EXPECT_NE(both.find("job overview/kc/warm/view1's output /base/renders/kc/warm/view1/overview.png and job "
                        "render/kc/warm/view1/overview's output /base/renders/kc/warm/view1/overview.png are the same file"),
              std::string::npos) << both;
    // A wavelength given twice makes two slices of one name.
    text = study_text();
    text.replace(text.find(R"("wavelengths": [450, 650.5])"), 27, R"("wavelengths": [450, 450.0])");
    const std::string twice = expand_error(parse_study(text, "/base", "s.json"));
    EXPECT_NE(twice.find("/base/brdf/kc/slice_450nm_ggx.csv are the same file: name another output"), std::string::npos)
        << twice;
    // A material table the study reads, where a BRDF job would write its slice.
    const fs::path folder = scratch("collision");
    fs::create_directories(folder / "brdf");
    { std::ofstream(folder / "brdf" / "slice_550nm_ghs.csv") << "wavelength_nm,n,k\n400,0.2,3\n700,0.2,4\n"; }
    const std::string brdf_only = R"({"parameters": {"material": "brdf/slice_550nm_ghs.csv", "sigma": 0.1,
        "corr_length": 2, "gamma": 3}, "models": [{"name": "ghs", "model": "ghs"}], "wavelengths": [550],
        "brdf_slices": {"theta_i": [0]}})";
    const std::string input = expand_error(parse_study(brdf_only, folder, "s.json"));
    EXPECT_NE(input.find("job slice/550nm/ghs's output " + (folder / "brdf/slice_550nm_ghs.csv").string() +
                         " would replace the input 'brdf/slice_550nm_ghs.csv' of job slice/550nm/ghs"),
              std::string::npos) << input;
    EXPECT_EQ(input.find('\n'), std::string::npos);
}

TEST(StudyJobs, SheetColumnsFollowThePanelCountAndUncroppedSheetsCropToTheSample) {
    EXPECT_EQ(sheet_columns(1, 0), 1);
    EXPECT_EQ(sheet_columns(3, 0), 3);
    EXPECT_EQ(sheet_columns(4, 0), 4);
    EXPECT_EQ(sheet_columns(5, 0), 3);
    EXPECT_EQ(sheet_columns(8, 0), 4);  // compare-models: seven models and the overview
    EXPECT_EQ(sheet_columns(9, 0), 3);
    EXPECT_EQ(sheet_columns(9, 2), 2);

    // Two models, no crop, no columns: one row of two, cropped to where they differ; sigma from the scene's default
    // (0.15 um), GGX within its validity there, and at sigma 0.01 um (g0 0.052) outside it.
    const Study s = parse_study(R"({
  "scene": ")" + kScene + R"(",
  "views": [1],
  "models": [{"name": "ggx", "label": "GGX", "model": "ggx_stats", "alpha_from": "measured"},
             {"name": "ghs", "model": "ghs"}],
  "surfaces": [{"name": "scene"}, {"name": "smooth", "sigma": 0.01}],
  "render": {"spp": 4, "width": 64, "height": 48}
})",
                                "/base", "s.json");
    int sheets = 0;
    for (const Job& j : expand(s)) {
        if (j.id == "sheet/scene/view1") {
            ++sheets;
            EXPECT_EQ(j.parameters["columns"], 2);
            EXPECT_EQ(j.parameters["crop_to_difference"], true);
            EXPECT_EQ(j.parameters["panels"][0][0], "GGX\nsigma 0.15 um, g0 11.7 at 550 nm");
            EXPECT_EQ(j.parameters["panels"][1][0], "ghs\nsigma 0.15 um, g0 11.7 at 550 nm");
        } else if (j.id == "sheet/smooth/view1") {
            ++sheets;
            EXPECT_EQ(j.parameters["panels"][0][0],
                      "GGX\nsigma 0.01 um, g0 0.0522 at 550 nm\n!GGX outside its validity (g0 0.052 < 1): no specular part");
        }
    }
    EXPECT_EQ(sheets, 2);
    EXPECT_EQ(render::scene_default(kScene, "sigma"), "0.15");
    EXPECT_EQ(render::scene_default(kScene, "no_such_parameter"), "");
    EXPECT_EQ(render::scene_default("/no/such/scene.xml", "sigma"), "");
}

TEST(StudyJobs, TablesOnlyWhereSeveralJobsShareThem) {
    // One view, no BRDF jobs, no overview: every model has one job, which builds its own tables.
    std::string text = study_text();
    for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
             {"[1, 2]", "[1]"}, {"\"lamps\"", "\"unused_lamps\""}}) text.replace(text.find(from), from.size(), to);
    nlohmann::json doc = nlohmann::json::parse(text);
    doc.erase("unused_lamps");
    doc.erase("brdf_slices");
    doc.erase("albedo");
    doc.erase("wavelengths");
    doc["render"].erase("crop");
    const std::vector<Job> jobs = expand(parse_study(doc.dump(), "/base", "s.json"));
    std::vector<std::string> ids;
    for (const Job& j : jobs) ids.push_back(j.id);
    EXPECT_EQ(ids, (std::vector<std::string>{"render/kc/view1/ggx", "render/kc/view1/ghs", "render/kc/view1/ssa",
                                             "sheet/kc/view1"}));
    EXPECT_THROW(expand(parse_study(R"({"scene": "absent.xml", "views": [1], "models": [{"name": "a"}], "render": {}})",
                                    "/nowhere", "s.json")),
                 Error);
}

// The albedo of an anisotropic model (the elliptical GGX) is tabulated over incidence azimuths 0, 15, .., 165 deg from
// the study's phi_i, an isotropic model's at phi_i alone; the azimuths' albedos differ, and repeat after 180 deg.
TEST(StudyRun, AlbedoOfAnAnisotropicModelOverIncidenceAzimuths) {
    const fs::path dir = scratch("albedo_azimuths");
    const Study s = parse_study(R"({"parameters": {"material": "Au"},
        "models": [{"name": "iso", "model": "ggx_stats", "alpha": 0.2},
                   {"name": "lay", "model": "ggx_stats", "alpha_from": "kc_link", "sigma": 0.1, "corr_length": 1,
                    "corr_length_v": 0.3, "lay_angle": 20, "gamma": 3}],
        "wavelengths": [550], "albedo": {"theta_i": [30, 60], "phi_i": 10}})",
                                dir, "s.json");
    const JobContext context{1, false, "testhost"};
    for (const Job& job : expand(s)) {
        if (job.kind == JobKind::albedo) {
            ASSERT_EQ(run_job(s, job, context)["status"], "done") << job.id;
        }
    }
    const auto rows = [&](const std::string& model) {
        std::ifstream in(dir / ("brdf/albedo_550nm_" + model + ".csv"));
        std::string line;
        std::getline(in, line);
        EXPECT_EQ(line, "model,theta_i,albedo,scatter,specular,phi_i_deg");
        std::vector<std::vector<double>> table;  // theta_i, albedo, phi_i_deg
        while (std::getline(in, line)) {
            std::stringstream cells(line);
            std::vector<std::string> cell(6);
            for (auto& c : cell) std::getline(cells, c, ',');
            table.push_back({std::stod(cell[1]), std::stod(cell[2]), std::stod(cell[5])});
        }
        return table;
    };
    const auto iso = rows("iso");
    ASSERT_EQ(iso.size(), 2u);
    EXPECT_EQ(iso[0][2], 10.0);
    const auto lay = rows("lay");
    ASSERT_EQ(lay.size(), 24u);
    for (std::size_t k = 0; k < 12; ++k) {
        EXPECT_DOUBLE_EQ(lay[2 * k][2], 10.0 + 15.0 * static_cast<double>(k));
        EXPECT_EQ(lay[2 * k + 1][0], 60.0);
    }
    // At 60 deg the albedo along the lay (phi_i 10 + 15 k nearest 20 deg) and across it (110 deg) differ.
    EXPECT_GT(std::abs(lay[1][1] - lay[13][1]), 1e-3);
}

// A surface from a height map (issue 33 item 6): surface_file and its preparation pass to the shipped scene, which
// reads the map (scenes/photo-setup/surface_map.xml); the sheet's caption names the map; a map that is not there is an
// error naming the study key, before any job runs.
TEST(StudyRun, AHeightMapSurfaceRendersWithTheShippedSceneAndTheCaptionNamesIt) {
    const fs::path dir = scratch("height_map");
    const std::string map = std::string(SURFSCATTER_SOURCE_DIR) + "/examples/data/kc_surface.gsf";
    const auto study = [&](const std::string& file) {
        return R"({"scene": ")" + kScene + R"(", "views": [1], "parameters": {"material": "Au"},
        "models": [{"name": "ggx", "label": "GGX", "model": "ggx_stats"}, {"name": "ssa", "model": "ghs_ssa"}],
        "surfaces": [{"name": "map", "surface_file": ")" + file + R"(", "form": "poly2"}],
        "render": {"spp": 1, "width": 16, "height": 12}})";
    };
    const Study s = parse_study(study(map), dir, "s.json");
    int renders = 0, sheets = 0;
    for (const Job& job : expand(s)) {
        if (job.kind == JobKind::render && job.id == "render/map/view1/ggx") {
            ++renders;
            EXPECT_EQ(job.parameters["defines"]["surface_file"], map);
            EXPECT_EQ(job.parameters["defines"]["form"], "poly2");
            const nlohmann::json report = run_job(s, job, JobContext{1, false, "testhost"});
            ASSERT_EQ(report["status"], "done") << report.dump();
            // The scene read the map (its note names the file) and rendered the plate.
            bool noted = false;
            for (const auto& note : report["notes"]) noted = noted || note.get<std::string>().find("kc_surface.gsf") != std::string::npos;
            EXPECT_TRUE(noted) << report.dump();
            EXPECT_EQ(io::read_image(dir / "renders/map/view1/ggx.exr").width, 16);
        } else if (job.kind == JobKind::sheet) {
            ++sheets;
            EXPECT_EQ(job.parameters["panels"][0][0], "GGX\nheight map kc_surface.gsf");
            EXPECT_EQ(job.parameters["panels"][1][0], "ssa\nheight map kc_surface.gsf");
        }
    }
    EXPECT_EQ(renders, 1);
    EXPECT_EQ(sheets, 1);

    const std::string missing = (dir / "no_such_map.gsf").string();
    try {
        parse_study(study(missing), dir, "s.json");
        ADD_FAILURE() << "a missing map was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "s.json: surfaces[0].surface_file: file not found: " + missing);
    }
}

// BRDF jobs run in process: the outputs, the report, the manifest's resume rule.
TEST(StudyRun, BrdfJobsWriteTablesAndTheManifestKnowsWhenTheyAreUpToDate) {
    const fs::path dir = scratch("brdf");
    nlohmann::json doc = nlohmann::json::parse(study_text());
    for (const char* key : {"scene", "views", "render", "lamps"}) doc.erase(key);
    doc["wavelengths"] = {550};
    Study s = parse_study(doc.dump(), dir, "s.json");
    const std::vector<Job> jobs = expand(s);
    const JobContext context{1, false, "testhost"};
    Manifest manifest(dir / "manifest.json", jobs, dir);
    for (const Job& job : jobs) {
        if (job.kind == JobKind::slice_plot || job.kind == JobKind::albedo_plot) continue;  // matplotlib: CLI tests
        const nlohmann::json report = run_job(s, job, context);
        ASSERT_EQ(report["status"], "done") << job.id << ": " << report.dump();
        EXPECT_EQ(report["host"], "testhost");
        EXPECT_GE(report["wall_seconds"].get<double>(), 0.0);
        EXPECT_EQ(report["outputs"].size(), job.outputs.size());
        manifest.record(job, report, 3);
        EXPECT_TRUE(manifest.up_to_date(job)) << job.id;
    }
    // The albedo table: one row per incidence angle, albedo in (0, 1] for gold at 550 nm.
    std::ifstream albedo(dir / "brdf/kc/albedo_550nm_ghs.csv");
    std::string line;
    std::getline(albedo, line);
    EXPECT_EQ(line, "model,theta_i,albedo,scatter,specular,phi_i_deg");
    int rows = 0;
    while (std::getline(albedo, line)) {
        ++rows;
        const double value = std::stod(line.substr(line.find(',', 4) + 1));
        EXPECT_GT(value, 0.5) << line;
        EXPECT_LE(value, 1.0) << line;
    }
    EXPECT_EQ(rows, 3);

    // Read back from disk: still up to date; a changed parameter, a touched or a missing output is not.
    const Manifest reread(dir / "manifest.json", jobs, dir);
    const Job* slice = nullptr;
    for (const Job& j : jobs)
        if (j.id == "slice/kc/550nm/ghs") slice = &j;
    ASSERT_NE(slice, nullptr);
    EXPECT_TRUE(reread.up_to_date(*slice));
    Job changed = *slice;
    changed.parameters["theta_i"] = {0, 46};
    EXPECT_FALSE(reread.up_to_date(changed));
    const fs::path csv = dir / slice->outputs[0];
    { std::ofstream(csv, std::ios::app) << "extra\n"; }
    EXPECT_FALSE(reread.up_to_date(*slice));
    fs::remove(csv);
    EXPECT_FALSE(reread.up_to_date(*slice));
    const nlohmann::json entry = nlohmann::json::parse(std::ifstream(dir / "manifest.json"))["jobs"][0];
    EXPECT_EQ(entry["rank"], 3);
    EXPECT_TRUE(entry.contains("finished"));
    EXPECT_TRUE(entry.contains("cpu_seconds"));
    // What each job waited for (scripts/study-scaling-estimate replays the schedule from it).
    for (const nlohmann::json& e : nlohmann::json::parse(std::ifstream(dir / "manifest.json"))["jobs"])
        if (e["id"] == slice->id) {
            EXPECT_EQ(e["needs"], nlohmann::json::array({"tables/kc/ghs"}));
        }

    // A bad parameter fails the job with a message naming it, and leaves no output behind.
    Job bad = *slice;
    bad.parameters["model_options"]["gamma"] = "0.5";
    { std::ofstream(csv) << "stale\n"; }
    const nlohmann::json report = run_job(s, bad, context);
    EXPECT_EQ(report["status"], "failed");
    EXPECT_NE(report["error"].get<std::string>().find("gamma must be between 1.01 and 100 (KC), got 0.5"), std::string::npos) << report.dump();
    EXPECT_FALSE(fs::exists(csv));
    Job unknown = *slice;
    unknown.parameters["model_options"]["lamp_power"] = "1";
    EXPECT_NE(run_job(s, unknown, context)["error"].get<std::string>().find("'lamp_power' is not a parameter of bsdf 'ghs'"),
              std::string::npos);
}

// A study in `dir` only (jobs built by hand), and a job of it run and expected done with `image` written.
Study study_in(const fs::path& dir) {
    Study s;
    s.folder = dir;
    return s;
}
void expect_done(const Study& s, const Job& job, const fs::path& image) {
    const nlohmann::json report = run_job(s, job, JobContext{1, false, "testhost"});
    EXPECT_EQ(report["status"], "done") << report.dump();
    EXPECT_TRUE(fs::exists(image));
}

TEST(StudyRun, ASheetCroppedToTheDifferenceWithCaptionsAndWarningsIsWritten) {
    const fs::path dir = scratch("sheet_crop");
    // Two 64 x 48 renders alike but for a 12 x 10 patch (the "sample"), and a missing third panel.
    fs::create_directories(dir / "renders");
    for (const char* name : {"a", "b"}) {
        io::Image image(64, 48, 3, 0.2f);
        for (int y = 20; y < 30; ++y)
            for (int x = 30; x < 42; ++x) image.at(x, y, 0) = name[0] == 'a' ? 0.9f : 0.1f;
        io::write_png(dir / "renders" / (std::string(name) + ".png"), image);
    }
    Job sheet;
    sheet.id = "sheet/view1";
    sheet.kind = JobKind::sheet;
    sheet.parameters = {{"title", "t"},
                        {"columns", 3},
                        {"crop_to_difference", true},
                        {"panels", nlohmann::json::array({nlohmann::json::array({"A\nsigma 0.15 um", "renders/a.png"}),
                                                          nlohmann::json::array({"B\n!outside", "renders/b.png"}),
                                                          nlohmann::json::array({"C", "renders/c.png"})})}};
    sheet.outputs = {"sheets/view1.png"};
    sheet.inputs = {"renders/a.png", "renders/b.png", "renders/c.png"};
    expect_done(study_in(dir), sheet, dir / "sheets/view1.png");
}

TEST(StudyRun, ASlicePlotWithTheStudysLabelsIsWritten) {
    const fs::path dir = scratch("slice_plot");
    fs::create_directories(dir / "brdf");
    for (const char* model : {"ghs", "ggx"}) {
        std::ofstream csv(dir / "brdf" / (std::string(model) + ".csv"));
        csv << "model,theta_i,theta_o_signed,brdf,specular\n";
        for (int t = -80; t <= 80; t += 10) csv << model << ",30," << t << "," << 1.0 / (1 + std::abs(t - 30)) << ",0\n";
    }
    Job plot;
    plot.id = "slice-plot/550nm";
    plot.kind = JobKind::slice_plot;
    plot.parameters = {{"title", "550 nm"},
                       {"parts", {"brdf/ghs.csv", "brdf/ggx.csv"}},
                       {"labels", {{"ghs", "GHS"}, {"ggx", "GGX (measured slope)"}}}};
    plot.outputs = {"brdf/slice_550nm.csv", "brdf/slice_550nm.png"};
    expect_done(study_in(dir), plot, dir / "brdf/slice_550nm.png");
}

TEST(StudyRun, ASheetWithoutAnyOfItsImagesFailsSayingWhy) {
    const fs::path dir = scratch("sheet");
    Study s;
    s.folder = dir;
    Job sheet;
    sheet.id = "sheet/view1";
    sheet.kind = JobKind::sheet;
    sheet.parameters = {{"title", "t"}, {"columns", 2}, {"panels", nlohmann::json::array({nlohmann::json::array({"GHS", "renders/view1/ghs.png"})})}};
    sheet.outputs = {"sheets/view1.png"};
    sheet.inputs = {"renders/view1/ghs.png"};
    const nlohmann::json report = run_job(s, sheet, JobContext{1, false, "testhost"});
    EXPECT_EQ(report["status"], "failed");
    EXPECT_EQ(report["error"], "none of the sheet's images exists (their jobs failed)");
    EXPECT_FALSE(fs::exists(dir / "sheets/view1.png"));
}

TEST(StudyRun, AnUnreadableManifestIsAnErrorNamingIt) {
    const fs::path dir = scratch("manifest");
    { std::ofstream(dir / "manifest.json") << "{\"jobs\": ["; }
    const std::vector<Job> jobs;
    try {
        Manifest m(dir / "manifest.json", jobs, dir);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("manifest.json: not valid JSON"), std::string::npos) << e.what();
    }
}

TEST(StudyRun, FingerprintsAreFnv1aOfTheBytes) {
    const fs::path file = scratch("fingerprint") / "a.txt";
    { std::ofstream(file, std::ios::binary) << "a"; }
    const auto f = fingerprint(file);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->bytes, 1u);
    EXPECT_EQ(f->fnv1a, "af63dc4c8601ec8c");  // FNV-1a 64 of "a" (the published test vector)
    EXPECT_FALSE(fingerprint(file.parent_path() / "absent"));
    // Only regular files: a hand-edited manifest naming a device or a folder makes its job out of date, no more.
    EXPECT_FALSE(fingerprint("/dev/zero"));
    EXPECT_FALSE(fingerprint(file.parent_path()));
}

}  // namespace
}  // namespace surfscatter::study
