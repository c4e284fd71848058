// Renders split into parts (what distributed/render.cpp gives each MPI rank), film states, and the scattering-model
// options read from text (a study's BRDF jobs) against the same plugin read from XML.
#include <gtest/gtest.h>

#include "render_test_util.hpp"
#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/render/model_parameters.hpp"

namespace surfscatter::render {
namespace {

// A rough metal plate and a diffuse floor under a point light and a sky, seen at an angle (many-bounce paths with
// several BSDF lobes), on a 37 x 29 film: 3 x 2 tiles, the last ones partial.
std::string plate_scene(const std::string& crop = "") {
    std::string xml = test::scene_xml(R"(
  <shape type="rectangle"><transform name="to_world"><scale value="0.6"/></transform>
    <bsdf type="roughconductor"><string name="material" value="Au"/><float name="alpha" value="0.2"/></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><scale value="3"/><translate z="-0.2"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.5, 0.3"/></bsdf></shape>
  <emitter type="point"><point name="position" x="0.5" y="0.4" z="1"/><spectrum name="intensity" value="2"/></emitter>
  <emitter type="constant"><spectrum name="radiance" value="0.1"/></emitter>)",
                           "0, -1.6, 1.4", "0, 0, 0", 60.0, 37);
    const std::string height = "<integer name=\"height\" value=\"37\"/>";
    return xml.replace(xml.find(height), height.size(), "<integer name=\"height\" value=\"29\"/>" + crop);
}

RenderOptions options_for(int part, int parts) {
    RenderOptions o;
    o.spp = 5;
    o.seed = 7;
    o.progress = false;
    o.part = part;
    o.parts = parts;
    return o;
}

void expect_same_state(const Film& a, const Film& b) {
    const std::vector<double> sa = a.state(), sb = b.state();
    ASSERT_EQ(sa.size(), sb.size());
    std::size_t different = 0;
    for (std::size_t i = 0; i < sa.size(); ++i) different += sa[i] == sb[i] ? 0 : 1;  // exact, bit for bit
    EXPECT_EQ(different, 0u);
}

TEST(RenderParts, PartsSumToTheWholeRenderBitForBit) {
    for (const std::string& crop : {std::string(), std::string(R"(<integer name="crop_offset_x" value="5"/>
        <integer name="crop_offset_y" value="3"/><integer name="crop_width" value="30"/><integer name="crop_height" value="21"/>)")}) {
        const auto scene = load_scene_from_string(plate_scene(crop), "plate.xml");
        const Film whole = render(*scene, options_for(0, 1));
        for (const int parts : {2, 3, 7}) {  // 7 parts of 6 tiles: one part renders nothing
            Film sum(whole.width(), whole.height());
            for (int part = 0; part < parts; ++part) {
                RenderOptions o = options_for(part, parts);
                o.threads = 1 + part % 2;  // and any thread count
                const Film piece = render(*scene, o);
                // Every pixel belongs to exactly one part: the others leave it untouched.
                const std::vector<double> state = piece.state();
                for (int y = 0; y < piece.height(); ++y)
                    for (int x = 0; x < piece.width(); ++x) {
                        const int tile = (y / 16) * ((piece.width() + 15) / 16) + x / 16;
                        const double count = state[(static_cast<std::size_t>(y) * piece.width() + x) * 5 + 4];
                        EXPECT_EQ(count, tile % parts == part ? 5.0 : 0.0) << x << "," << y << " part " << part;
                    }
                sum.accumulate(piece);
            }
            SCOPED_TRACE(parts);
            expect_same_state(sum, whole);
        }
    }
}

TEST(RenderParts, SharedProgressCountsPixelSamplesOfAllParts) {
    const auto scene = load_scene_from_string(plate_scene(), "plate.xml");
    Progress progress("test", 37 * 29 * 5, false);
    for (int part = 0; part < 3; ++part) {
        RenderOptions o = options_for(part, 3);
        o.shared_progress = &progress;
        render(*scene, o);
    }
    EXPECT_EQ(progress.done(), 37u * 29u * 5u);
}

TEST(RenderParts, FilmStateRoundTripsAndChecksItsSize) {
    const Film whole = render(*load_scene_from_string(plate_scene(), "plate.xml"), options_for(0, 1));
    Film copy(whole.width(), whole.height());
    copy.set_state(whole.state());
    expect_same_state(copy, whole);
    EXPECT_EQ(copy.xyz(20, 14).y, whole.xyz(20, 14).y);
    EXPECT_THROW(copy.set_state(std::vector<double>(10)), Error);
    Film other(4, 4);
    EXPECT_THROW(other.accumulate(whole), Error);
    EXPECT_THROW(render(*load_scene_from_string(plate_scene(), "plate.xml"), options_for(3, 3)), Error);
}

TEST(ModelParameters, TextReadsAsTheXmlPluginDoes) {
    // ggx_stats: alpha from the measured slopes unless told otherwise, as in a scene.
    const bsdf::ModelOptions text = scattering_model_options(
        "ggx_stats", {{"sigma", "0.15"}, {"corr_length", "4"}, {"gamma", "3"}, {"material", "Au"}}, "study");
    EXPECT_EQ(text.model, bsdf::ModelKind::ggx);
    EXPECT_EQ(text.alpha_from, bsdf::AlphaFrom::measured);
    EXPECT_EQ(text.surface.sigma, 0.15);
    EXPECT_EQ(text.material, "Au");
    const bsdf::ModelOptions two_scale = scattering_model_options(
        "two_scale", {{"sigma", "0.15"}, {"corr_length", "4"}, {"gamma", "3"}, {"cutoff_wavelengths", "50"},
                      {"renormalization", "false"}}, "study");
    EXPECT_EQ(two_scale.cutoff_wavelengths, 50.0);
    EXPECT_FALSE(two_scale.renormalization);
    // Elliptical statistics by the SurfaceOptions names (a study's model or surface parameters, -D defines).
    const bsdf::ModelOptions brushed = scattering_model_options(
        "ggx_stats", {{"sigma", "0.1"}, {"corr_length", "20"}, {"corr_length_v", "1"}, {"lay_angle", "90"}, {"gamma", "4"}},
        "study");
    EXPECT_EQ(brushed.surface.corr_length_v, 1.0);
    EXPECT_EQ(brushed.surface.lay_angle, 90.0);
    // two_scale takes them too: an anisotropic macro NDF and micro lobe.
    const bsdf::ModelOptions brushed_two_scale = scattering_model_options(
        "two_scale", {{"sigma", "0.05"}, {"corr_length", "2"}, {"corr_length_v", "0.8"}, {"lay_angle", "30"},
                      {"gamma", "4"}, {"cutoff_wavelengths", "50"}}, "study");
    EXPECT_FALSE(bsdf::make_bsdf(brushed_two_scale)->isotropic());
}

TEST(ModelParameters, TextErrorsNameTheOriginAndTheParameter) {
    const auto message = [](const std::string& type, const std::map<std::string, std::string>& p) {
        try {
            scattering_model_options(type, p, "models[1]");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    const std::map<std::string, std::string> kc = {{"sigma", "0.1"}, {"corr_length", "2"}, {"gamma", "3"}};
    auto with = [&](const char* k, const char* v) {
        auto m = kc;
        m[k] = v;
        return m;
    };
    EXPECT_EQ(message("ghs", with("alpha_from", "measured")),
              "models[1]: alpha_from: parameter 'alpha_from' does not apply to bsdf 'ghs': used by model ggx_stats only");
    EXPECT_EQ(message("ghs", with("psd", "kcc")), "models[1]: psd must be one of kc | gaussian | file | measured, got 'kcc'");
    EXPECT_NE(message("ghs", with("alpha_form", "measured")).find("'alpha_form' is not a parameter of bsdf 'ghs'"),
              std::string::npos);
    EXPECT_NE(message("ghs", with("sigma", "0.1x")).find("models[1]: sigma: '0.1x' is not a finite number"),
              std::string::npos);
    EXPECT_EQ(message("ghs", with("gamma", "0.5")), "models[1]: bsdf 'ghs': gamma must be between 1.01 and 100 (KC), got 0.5");
    EXPECT_NE(message("ghs", with("renormalization", "yes")).find("true or false"), std::string::npos);
    EXPECT_NE(message("roughconductor", kc).find("unknown scattering model 'roughconductor'"), std::string::npos);
    EXPECT_EQ(message("ggx_stats", {{"alpha", "0.1"}, {"lay_angle", "30"}}),
              "models[1]: lay_angle: parameter 'lay_angle' does not apply to bsdf 'ggx_stats': model ggx_stats with "
              "alpha_from none takes no surface");
    EXPECT_EQ(message("ghs", with("corr_length_v", "-1")),
              "models[1]: bsdf 'ghs': corr_length_v must be between 1e-09 and 1e+09 um, got -1");
}

}  // namespace
}  // namespace surfscatter::render
