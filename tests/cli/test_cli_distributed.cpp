// End-to-end under Open MPI's mpirun on this host (2 ranks; 3 oversubscribed): one render over ranks equal to the
// single-process render bit for bit, failing and killed ranks, Ctrl-C; studies over ranks and without mpirun: every
// output, manifest and sheet, a rerun that does nothing, an interrupted study resumed, a bad job among good ones.
// Every command runs with a deadline, so a hang fails the test instead of stalling the suite.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "background_process.hpp"
#include "surfscatter/io/image.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using surfscatter::test::BackgroundProcess;

namespace {

constexpr double kDeadline = 240;  // seconds: far beyond any of these runs, even on a loaded 2-core machine

// One folder per test process: ctest runs the cases in parallel, and other worktrees' suites share /tmp.
fs::path temp_dir() {
    const fs::path dir = fs::temp_directory_path() / ("surfscatter_test_cli_distributed_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir;
}

class Distributed : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        // CI runs as root; Open MPI refuses that unless told.
        setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
        setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    }
    // The renders and studies are kept for a look when a test failed.
    static void TearDownTestSuite() {
        if (::testing::UnitTest::GetInstance()->Passed()) fs::remove_all(temp_dir());
    }

    // mpirun -np N on this host: more ranks than cores allowed; shared memory without the single-copy mechanism
    // that containers often forbid.
    static std::vector<std::string> mpirun(int ranks, std::vector<std::string> extra = {}) {
        std::vector<std::string> argv = {SURFSCATTER_MPIEXEC, "-np", std::to_string(ranks), "--oversubscribe", "--mca",
                                         "btl", "self,vader", "--mca", "btl_vader_single_copy_mechanism", "none"};
        argv.insert(argv.end(), extra.begin(), extra.end());
        return argv;
    }

    static std::vector<std::string> cli(std::vector<std::string> launcher, const std::vector<std::string>& args) {
        launcher.push_back(SURFSCATTER_CLI);
        launcher.insert(launcher.end(), args.begin(), args.end());
        return launcher;
    }

    struct Result {
        int status;
        std::string err;
    };
    static Result run(const std::vector<std::string>& argv, const std::string& name) {
        BackgroundProcess p(argv, temp_dir() / (name + ".out"), temp_dir() / (name + ".err"));
        const int status = p.wait(kDeadline);
        return {status, p.err()};
    }
};

// Several materials and light paths, float32 RGBA, 45 x 37 pixels: 3 x 3 tiles, the last ones partial.
const char* kScene = R"(<scene version="3.0.0">
  <default name="spp" value="4"/>
  <integrator type="path"><integer name="max_depth" value="5"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="55"/>
    <transform name="to_world"><lookat origin="0, -1.8, 1.3" target="0, 0, 0" up="0, 0, 1"/></transform>
    <film type="hdrfilm"><integer name="width" value="45"/><integer name="height" value="37"/>
      <string name="pixel_format" value="rgba"/><string name="component_format" value="float32"/></film>
    <sampler type="independent"><integer name="sample_count" value="$spp"/><integer name="seed" value="5"/></sampler>
  </sensor>
  <shape type="rectangle"><transform name="to_world"><scale value="0.5"/></transform>
    <bsdf type="roughconductor"><string name="material" value="Cu"/><float name="alpha" value="0.15"/></bsdf></shape>
  <shape type="sphere"><point name="center" x="0.3" y="0.2" z="0.2"/><float name="radius" value="0.2"/>
    <bsdf type="dielectric"/></shape>
  <shape type="rectangle"><transform name="to_world"><scale value="4"/><translate z="-0.1"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.5, 0.6, 0.4"/></bsdf></shape>
  <emitter type="point"><point name="position" x="-0.5" y="-0.3" z="1.2"/><spectrum name="intensity" value="3"/></emitter>
  <emitter type="constant"><spectrum name="radiance" value="0.05"/></emitter>
</scene>
)";

fs::path scene_file() {
    const fs::path path = temp_dir() / "scene.xml";
    std::ofstream(path) << kScene;
    return path;
}

std::vector<float> pixels(const fs::path& exr) { return surfscatter::io::read_image(exr).pixels; }

TEST_F(Distributed, RenderOverRanksEqualsTheSingleProcessRenderBitForBit) {
    const fs::path scene = scene_file();
    const fs::path one = temp_dir() / "one.exr", two = temp_dir() / "two.exr", three = temp_dir() / "three.exr";
    for (const fs::path& p : {one, two, three}) fs::remove(p);
    Result r = run(cli({}, {"render", scene.string(), "--quiet", "-o", one.string()}), "render1");
    ASSERT_EQ(r.status, 0) << r.err;
    r = run(cli(mpirun(2), {"render", scene.string(), "--quiet", "-o", two.string()}), "render2");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("on 2 ranks"), std::string::npos) << r.err;
    r = run(cli(mpirun(3), {"render", scene.string(), "--threads", "1", "-o", three.string()}), "render3");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("100.0%"), std::string::npos) << "rank 0 draws the combined progress: " << r.err;

    const std::vector<float> a = pixels(one), b = pixels(two), c = pixels(three);
    ASSERT_EQ(a.size(), 45u * 37u * 4u);
    ASSERT_EQ(a.size(), b.size());
    ASSERT_EQ(a.size(), c.size());
    std::size_t differ2 = 0, differ3 = 0, lit = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        differ2 += a[i] == b[i] ? 0 : 1;
        differ3 += a[i] == c[i] ? 0 : 1;
        lit += a[i] > 0 ? 1 : 0;
    }
    EXPECT_EQ(differ2, 0u);
    EXPECT_EQ(differ3, 0u);
    EXPECT_GT(lit, a.size() * 9 / 10);  // not a trivially black image
    EXPECT_TRUE(fs::exists(temp_dir() / "two.png"));

    // A realistic scene with a lobe-table model, compared as written (EXR and PNG bytes).
    const std::string photo = std::string(SURFSCATTER_SOURCE_DIR) + "/scenes/photo-setup/scene.xml";
    const std::vector<std::string> args = {"render", photo, "-D", "view=2", "-D", "model=ghs", "-D", "width=48",
                                           "-D", "height=36", "--spp", "2", "--quiet", "-o"};
    auto with_output = [&](const fs::path& out) {
        auto a2 = args;
        a2.push_back(out.string());
        return a2;
    };
    ASSERT_EQ(run(cli({}, with_output(temp_dir() / "ghs1.exr")), "ghs1").status, 0);
    ASSERT_EQ(run(cli(mpirun(2), with_output(temp_dir() / "ghs2.exr")), "ghs2").status, 0);
    for (const char* ext : {".exr", ".png"}) {
        std::ifstream x(temp_dir() / (std::string("ghs1") + ext), std::ios::binary), y(temp_dir() / (std::string("ghs2") + ext), std::ios::binary);
        const std::string bx((std::istreambuf_iterator<char>(x)), {}), by((std::istreambuf_iterator<char>(y)), {});
        EXPECT_FALSE(bx.empty());
        EXPECT_EQ(bx, by) << ext;
    }
}

TEST_F(Distributed, AFailingRankEndsTheRunNamingItsRankAndError) {
    const fs::path scene = scene_file();
    const std::string out = (temp_dir() / "fail.exr").string();
    // mpirun -np 1 A : -np 1 B: rank 1 cannot read its scene.
    std::vector<std::string> argv = cli(mpirun(1), {"render", scene.string(), "--quiet", "-o", out});
    argv.insert(argv.end(), {":", "-np", "1", SURFSCATTER_CLI, "render", (temp_dir() / "absent.xml").string(), "--quiet",
                              "-o", out});
    Result r = run(argv, "fail_scene");
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("rank 1: scene file not found: "), std::string::npos) << r.err;

    // Ranks asked for different renders: refused before any work (their films could not be summed).
    argv = cli(mpirun(1), {"render", scene.string(), "--spp", "4", "--quiet", "-o", out});
    argv.insert(argv.end(), {":", "-np", "1", SURFSCATTER_CLI, "render", scene.string(), "--spp", "8", "--quiet", "-o", out});
    r = run(argv, "fail_same");
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("rank 1: the render (scene, film, spp, seed) is not the same as on rank 0"), std::string::npos)
        << r.err;

    // Every rank fails alike: one message, as without MPI.
    r = run(cli(mpirun(2), {"render", (temp_dir() / "absent.xml").string(), "-o", out}), "fail_all");
    EXPECT_EQ(r.status, 2);
    const std::string message = "surfscatter: error: scene file not found";
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find(message), r.err.rfind(message)) << r.err;
}

TEST_F(Distributed, AKilledRankEndsTheWholeRunInsteadOfHanging) {
    const fs::path scene = scene_file();
    BackgroundProcess p(cli(mpirun(2), {"render", scene.string(), "-D", "spp=100000", "--quiet", "-o",
                                        (temp_dir() / "killed.exr").string()}),
                        temp_dir() / "killed.out", temp_dir() / "killed.err");
    std::vector<pid_t> ranks;
    for (int i = 0; i < 500 && ranks.size() < 2; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        ranks = p.children();
    }
    ASSERT_EQ(ranks.size(), 2u) << p.err();
    std::this_thread::sleep_for(std::chrono::seconds(1));  // rendering
    ASSERT_TRUE(p.running()) << p.err();
    kill(ranks.back(), SIGKILL);
    const int status = p.wait(60);
    EXPECT_NE(status, -1) << "mpirun still running a minute after a rank died";
    EXPECT_NE(status, 0);
    EXPECT_NE(p.err().find("rank"), std::string::npos) << p.err();
}

// Starts a long render over 2 ranks, waits until it is under way, sends `sig` to mpirun and checks that rank 0
// wrote the image of every rank's completed passes.
void interrupt_render(const std::vector<std::string>& launcher, int sig, const std::string& name) {
    const fs::path scene = scene_file(), exr = temp_dir() / (name + ".exr");
    fs::remove(exr);
    std::vector<std::string> argv = launcher;
    for (const std::string& a : {std::string(SURFSCATTER_CLI), std::string("render"), scene.string(), std::string("-D"),
                                 std::string("spp=12800"), std::string("-o"), exr.string()})
        argv.push_back(a);
    BackgroundProcess p(argv, temp_dir() / (name + ".out"), temp_dir() / (name + ".err"));
    // Rank 0's progress line (stderr is a file: "render: started") shows that the ranks are rendering.
    for (int i = 0; i < 3000 && p.err().find("render: started") == std::string::npos; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_TRUE(p.running()) << p.err();
    p.signal(sig);
    p.wait(kDeadline);
    EXPECT_NE(p.err().find("(interrupted)"), std::string::npos) << p.err();
    ASSERT_TRUE(fs::exists(exr)) << p.err();
    // Every pixel has samples: both ranks' tiles are in the image.
    const std::vector<float> image = pixels(exr);
    std::size_t empty = 0;
    for (std::size_t i = 3; i < image.size(); i += 4) empty += image[i] > 0 ? 0 : 1;  // alpha
    EXPECT_EQ(empty, 0u);
}

TEST_F(Distributed, CtrlCWritesTheImageOfEveryRankSoFar) {
    // SIGINT to mpirun reaches the ranks as SIGTERM, and SIGKILL follows odls_base_sigkill_timeout seconds later:
    // the ranks stop within a sample, but summing and writing the image must fit in that time; 5 s here (default
    // 1) for a heavily loaded machine (docs/DISTRIBUTED.md).
    interrupt_render(mpirun(2, {"--mca", "odls_base_sigkill_timeout", "5"}), SIGINT, "ctrl_c");
}

TEST_F(Distributed, SigusrOneStopsEveryRankAtOnce) {
    interrupt_render(mpirun(2), SIGUSR1, "usr1");  // mpirun forwards it to every rank immediately
}

// ---------------------------------------------------------------------------------------------------- studies

// 2 views x 3 models of scenes/photo-setup, tiny, cropped around the plate (with overviews and sheets).
json small_study(int spp, int width, int height, bool crop) {
    json s = {{"scene", std::string(SURFSCATTER_SOURCE_DIR) + "/scenes/photo-setup/scene.xml"},
              {"views", {1, 2}},
              {"models",
               {{{"name", "ggx_measured"}, {"label", "GGX (measured)"}, {"model", "ggx_stats"}},
                {{"name", "ggx_smoothed"}, {"model", "ggx_stats"}, {"alpha_from", "smoothed"}, {"smoothing", 1}},
                {{"name", "ghs"}, {"label", "GHS"}, {"model", "ghs"}}}},
              {"render", {{"spp", spp}, {"width", width}, {"height", height}}}};
    if (crop) s["render"]["crop"] = {{"focus", {0.09, 0, 0.001}}, {"radius", 0.06}};
    return s;
}

fs::path write_study(const std::string& name, const json& study) {
    const fs::path dir = temp_dir() / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "study.json") << study.dump(2);
    return dir;
}

json manifest_of(const fs::path& dir) {
    std::ifstream in(dir / "manifest.json");
    return json::parse(in);
}

std::map<std::string, json> entries(const json& manifest) {
    std::map<std::string, json> out;
    for (const json& e : manifest["jobs"]) out[e["id"].get<std::string>()] = e;
    return out;
}

std::string bytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST_F(Distributed, StudyOverRanksMakesEveryOutputTheManifestAndTheSheetsAndARerunDoesNothing) {
    const fs::path dir = write_study("study", small_study(2, 128, 96, true));
    Result r = run(cli(mpirun(2), {"study", (dir / "study.json").string(), "--quiet"}), "study_mpi");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("to run on 2 ranks"), std::string::npos) << r.err;

    const auto jobs = entries(manifest_of(dir));
    std::set<std::string> renders, sheets;
    std::set<int> ranks;
    for (const auto& [id, e] : jobs) {
        EXPECT_EQ(e["status"], "done") << id;
        for (const char* key : {"parameters", "outputs", "wall_seconds", "cpu_seconds", "rank", "host", "finished"})
            EXPECT_TRUE(e.contains(key)) << id << " has no " << key;
        for (const json& o : e["outputs"]) {
            EXPECT_TRUE(fs::exists(dir / o["path"].get<std::string>())) << o;
            EXPECT_EQ(fs::file_size(dir / o["path"].get<std::string>()), o["bytes"].get<std::uintmax_t>());
        }
        ranks.insert(e["rank"].get<int>());
        if (e["kind"] == "render") renders.insert(id);
        if (e["kind"] == "sheet") sheets.insert(id);
    }
    EXPECT_EQ(renders, (std::set<std::string>{"render/view1/ggx_measured", "render/view1/ggx_smoothed", "render/view1/ghs",
                                              "render/view2/ggx_measured", "render/view2/ggx_smoothed", "render/view2/ghs"}));
    EXPECT_EQ(sheets, (std::set<std::string>{"sheet/view1", "sheet/view2"}));
    EXPECT_EQ(ranks, (std::set<int>{0, 1}));  // both ranks pulled jobs
    EXPECT_TRUE(fs::exists(dir / "sheets/view1.png"));
    EXPECT_TRUE(fs::exists(dir / "renders/view2/overview.png"));
    EXPECT_EQ(jobs.at("render/view2/ghs")["parameters"]["defines"]["view"], "2");

    // Again: nothing to run, nothing rewritten.
    const std::string manifest_before = bytes(dir / "manifest.json");
    const auto sheet_time = fs::last_write_time(dir / "sheets/view2.png");
    r = run(cli(mpirun(2), {"study", (dir / "study.json").string()}), "study_mpi_again");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find(fmt::format("{} jobs, {} up to date, 0 to run", jobs.size(), jobs.size())), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(fmt::format("complete, all {} jobs up to date", jobs.size())), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("0 of 0 jobs run"), std::string::npos) << r.err;
    EXPECT_EQ(fs::last_write_time(dir / "sheets/view2.png"), sheet_time);
    EXPECT_EQ(entries(json::parse(bytes(dir / "manifest.json"))), entries(json::parse(manifest_before)));

    // The same study without mpirun, elsewhere: the same jobs and the same images.
    const fs::path alone = write_study("study_alone", small_study(2, 128, 96, true));
    r = run(cli({}, {"study", (alone / "study.json").string(), "--quiet"}), "study_alone");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("to run in this process"), std::string::npos) << r.err;
    EXPECT_EQ(entries(manifest_of(alone)).size(), jobs.size());
    for (const std::string& id : renders) {
        const std::string exr = jobs.at(id)["outputs"][0]["path"];
        EXPECT_EQ(bytes(dir / exr), bytes(alone / exr)) << exr;
    }
}

TEST_F(Distributed, AnInterruptedStudyResumesAndCompletes) {
    const fs::path dir = write_study("resume", small_study(24, 160, 120, false));
    BackgroundProcess p(cli(mpirun(2), {"study", (dir / "study.json").string(), "--quiet"}), temp_dir() / "resume.out",
                        temp_dir() / "resume.err");
    // Interrupted once two renders are on record, by SIGUSR1: mpirun forwards it to the ranks at once, where its
    // SIGINT reaches them only as a SIGTERM after a delay, long enough on an idle machine for every remaining job,
    // sheets included, to finish first (the test then had nothing to resume).
    const auto done_renders = [&] {
        int n = 0;
        if (fs::exists(dir / "manifest.json"))
            for (const auto& [id, e] : entries(manifest_of(dir))) n += e["kind"] == "render" && e["status"] == "done";
        return n;
    };
    for (int i = 0; i < 10000 && p.running() && done_renders() < 2; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_TRUE(p.running()) << "the study ended before it could be interrupted: " << p.err();
    p.signal(SIGUSR1);
    EXPECT_NE(p.wait(kDeadline), 0);
    const auto before = entries(manifest_of(dir));
    int done_before = 0;
    for (const auto& [id, e] : before) done_before += e["status"] == "done";
    ASSERT_GE(done_before, 2);
    ASSERT_FALSE(fs::exists(dir / "sheets/view2.png"));

    const Result r = run(cli(mpirun(2), {"study", (dir / "study.json").string(), "--quiet"}), "resume_again");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto after = entries(manifest_of(dir));
    for (const auto& [id, e] : after) EXPECT_EQ(e["status"], "done") << id;
    EXPECT_TRUE(fs::exists(dir / "sheets/view1.png"));
    EXPECT_TRUE(fs::exists(dir / "sheets/view2.png"));
    // What was done before was not done again.
    for (const auto& [id, e] : before)
        if (e["status"] == "done" && e["kind"] != "tables") {
            EXPECT_EQ(after.at(id)["finished"], e["finished"]) << id;
        }
}

TEST_F(Distributed, AJobWithABadParameterFailsNamingItWhileTheOthersComplete) {
    json study = small_study(2, 96, 72, false);
    study["models"].push_back({{"name", "bad"}, {"model", "ghs"}, {"gamma", 0.5}});
    const fs::path dir = write_study("bad", study);
    const Result r = run(cli(mpirun(2), {"study", (dir / "study.json").string(), "--quiet"}), "study_bad");
    EXPECT_EQ(r.status, 2) << r.err;
    const std::string listed = r.err.substr(r.err.find("jobs failed:"));
    for (const char* id : {"render/view1/bad", "render/view2/bad"})
        EXPECT_NE(listed.find(std::string(id) + ": "), std::string::npos) << id << " not listed: " << r.err;
    EXPECT_NE(listed.find("gamma must be between 1.01 and 100 (KC), got 0.5"), std::string::npos) << r.err;
    EXPECT_EQ(listed.find("ggx_measured"), std::string::npos) << r.err;
    const auto jobs = entries(manifest_of(dir));
    EXPECT_EQ(jobs.at("render/view1/bad")["status"], "failed");
    EXPECT_FALSE(fs::exists(dir / "renders/view1/bad.exr"));
    for (const char* good : {"render/view1/ghs", "render/view2/ggx_measured", "sheet/view1", "sheet/view2"})
        EXPECT_EQ(jobs.at(good)["status"], "done") << good;
    EXPECT_TRUE(fs::exists(dir / "sheets/view2.png"));  // with the bad model's panel marked missing
}

}  // namespace
