// The integrators and the film: direct against path with max_depth 2 (equal in expectation), hide_emitters and the
// alpha channel, aov refused, and hdrfilm writing the EXR channels and sample type the scene asks for.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <fmt/format.h>

#include "render_test_util.hpp"
#include "surfscatter/io/image.hpp"
#include "surfscatter/spectrum/color.hpp"

using namespace surfscatter;
using namespace surfscatter::render;
using namespace surfscatter::render::test;
namespace fs = std::filesystem;

namespace {

// Glossy and diffuse surfaces under an area light and a sky, plus (kSpot) a spot light.
const char* kSpot = R"(<emitter type="spot"><float name="intensity" value="3"/><transform name="to_world">
    <lookat origin="1, -1, 2" target="0, 0, 0"/></transform></emitter>)";
const char* kLitScene = R"(
    <shape type="rectangle"><transform name="to_world"><scale value="5"/></transform>
        <bsdf type="roughplastic"><float name="alpha" value="0.2"/><rgb name="diffuse_reflectance" value="0.3, 0.5, 0.2"/></bsdf></shape>
    <shape type="sphere"><point name="center" x="0.4" y="0" z="0.5"/><float name="radius" value="0.5"/>
        <bsdf type="roughconductor"><float name="alpha" value="0.15"/><string name="material" value="Cu"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><scale value="0.4"/><rotate x="1" angle="180"/><translate x="-0.8" z="2"/></transform>
        <emitter type="area"><rgb name="radiance" value="6, 5, 4"/></emitter></shape>
    <emitter type="constant"><float name="radiance" value="0.05"/></emitter>)";

}  // namespace

TEST(Integrators, DirectEqualsPathWithMaxDepthTwo) {
    // BSDF sampling alone cannot reach the spot light, so that variant is compared on the scene without it.
    for (const bool spot : {true, false}) {
        const std::string body = std::string(kLitScene) + (spot ? kSpot : "");
        const MeanY reference = mean_y_over_seeds(
            scene_xml(body, "0, -3, 2", "0, 0, 0.3", 35, 12, R"(<integrator type="path"><integer name="max_depth" value="2"/></integrator>)"),
            32, 8);
        std::printf("[direct vs path] spot %d, path max_depth 2: %.5f +- %.5f\n", spot, reference.mean, reference.standard_error);
        const std::vector<std::string> variants =
            spot ? std::vector<std::string>{R"(<integrator type="direct"/>)",
                                            R"(<integrator type="direct"><integer name="emitter_samples" value="3"/><integer name="bsdf_samples" value="1"/></integrator>)",
                                            R"(<integrator type="direct"><integer name="shading_samples" value="2"/></integrator>)"}
                 : std::vector<std::string>{R"(<integrator type="direct"><integer name="emitter_samples" value="0"/><integer name="bsdf_samples" value="2"/></integrator>)",
                                            R"(<integrator type="direct"><integer name="emitter_samples" value="2"/><integer name="bsdf_samples" value="0"/></integrator>)"};
        for (const std::string& direct : variants) {
            const MeanY y = mean_y_over_seeds(scene_xml(body, "0, -3, 2", "0, 0, 0.3", 35, 12, direct), 32, 8);
            std::printf("[direct vs path] spot %d, %-120s %.5f +- %.5f\n", spot, direct.c_str(), y.mean, y.standard_error);
            EXPECT_NEAR(y.mean, reference.mean, 4 * std::hypot(y.standard_error, reference.standard_error)) << direct;
        }
    }
    EXPECT_NE(load_error(scene_xml("", "0, 0, 3", "0, 0, 0", 1, 8, R"(<integrator type="direct"><integer name="shading_samples" value="2"/>
        <integer name="bsdf_samples" value="1"/></integrator>)")).find("either shading_samples"), std::string::npos);
    const std::string aov = load_error(scene_xml("", "0, 0, 3", "0, 0, 0", 1, 8, R"(<integrator type="aov"/>)"));
    EXPECT_NE(aov.find("integrator 'aov' is not supported"), std::string::npos) << aov;
}

TEST(Integrators, HideEmittersAndAlpha) {
    // The camera sees an area light (left half) and the empty sky (right half) above a floor it does not see.
    const std::string body = R"(<shape type="rectangle"><transform name="to_world"><scale value="0.5"/><translate x="-0.5"/></transform>
        <emitter type="area"><spectrum name="radiance" value="360:1, 830:1"/></emitter></shape>)";
    for (const char* type : {"path", "direct"}) {
        for (bool hide : {false, true}) {
            const std::string integrator =
                fmt::format(R"(<integrator type="{}"><boolean name="hide_emitters" value="{}"/></integrator>)", type, hide);
            const Film film = render_string(scene_xml(body, "0, 0, 3", "0, 0, 0", 36, 8, integrator), 64);
            // Column 1 sees the emitter, column 6 nothing (Y of a flat unit spectrum is 1 up to the wavelength noise).
            EXPECT_NEAR(film.xyz(1, 4).y, hide ? 0.0 : 1.0, 0.03) << type;
            EXPECT_NEAR(film.alpha(1, 4), 1.0, 1e-12) << type;
            EXPECT_EQ(film.alpha(6, 4), 0.0) << type;
        }
        // A visible environment covers every pixel unless it is hidden (Mitsuba's alpha).
        for (bool hide : {false, true}) {
            const std::string sky = body + R"(<emitter type="constant"><float name="radiance" value="0.2"/></emitter>)";
            const std::string integrator =
                fmt::format(R"(<integrator type="{}"><boolean name="hide_emitters" value="{}"/></integrator>)", type, hide);
            const Film film = render_string(scene_xml(sky, "0, 0, 3", "0, 0, 0", 36, 8, integrator), 64);
            EXPECT_NEAR(film.alpha(6, 4), hide ? 0.0 : 1.0, 1e-12) << type;
            EXPECT_NEAR(film.xyz(6, 4).y, hide ? 0.0 : 0.2, 0.006) << type;
        }
    }
}

// Non-finite spectral samples are counted, not silently dropped: none on an ordinary scene (every sample of every
// pixel accounted for), and the note the CLI, Python and study jobs print names their number.
TEST(Integrators, NonFiniteSamplesAreCountedAndReported) {
    auto scene = load_scene_from_string(scene_xml(kLitScene, "0, -3, 2", "0, 0, 0.3", 35, 12), "test.xml");
    RenderOptions options;
    options.spp = 8;
    options.progress = false;
    RenderStats stats;
    surfscatter::render::render(*scene, options, &stats);
    EXPECT_EQ(stats.nonfinite_samples, 0u);
    EXPECT_EQ(stats.samples_per_pixel, 8);
    EXPECT_EQ(nonfinite_note(stats), "");
    stats.nonfinite_samples = 3;
    EXPECT_NE(nonfinite_note(stats).find("3 spectral samples had a NaN or infinite radiance"), std::string::npos)
        << nonfinite_note(stats);
}

TEST(Film, WritesTheRequestedPixelAndComponentFormats) {
    const fs::path dir = temp_dir("test_film");
    const std::string body = R"(<shape type="rectangle"><transform name="to_world"><scale value="0.5"/><translate x="-0.5"/></transform>
        <emitter type="area"><rgb name="radiance" value="0.8, 0.4, 0.1"/></emitter></shape>)";
    struct Case {
        const char* pixel_format;
        const char* component_format;
        std::vector<std::string> channels;
    };
    const Case cases[] = {{"rgb", "float16", {"B", "G", "R"}},       {"rgba", "float32", {"A", "B", "G", "R"}},
                          {"luminance", "float32", {"Y"}},           {"luminance_alpha", "float16", {"A", "Y"}},
                          {"xyz", "float32", {"X", "Y", "Z"}},       {"xyza", "float16", {"A", "X", "Y", "Z"}}};
    for (const Case& c : cases) {
        const std::string xml = fmt::format(R"(<scene version="3.0.0">
            <sensor type="perspective"><float name="fov" value="36"/>
                <transform name="to_world"><lookat origin="0, 0, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
                <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/>
                    <string name="pixel_format" value="{}"/><string name="component_format" value="{}"/>
                    <rfilter type="box"/></film>
                <sampler type="independent"><integer name="sample_count" value="64"/></sampler></sensor>{}</scene>)",
                                            c.pixel_format, c.component_format, body);
        auto scene = load_scene_from_string(xml, dir / "scene.xml");
        RenderOptions options;
        options.progress = false;
        const Film film = surfscatter::render::render(*scene, options);
        const fs::path exr = dir / fmt::format("{}.exr", c.pixel_format);
        write_film(film, scene->film, exr);
        Imf::InputFile file(exr.c_str());
        std::vector<std::string> names;
        for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
            names.push_back(it.name());
            EXPECT_EQ(it.channel().type, std::string(c.component_format) == "float16" ? Imf::HALF : Imf::FLOAT) << c.pixel_format;
        }
        EXPECT_EQ(names, c.channels) << c.pixel_format;
        EXPECT_TRUE(fs::exists(dir / fmt::format("{}.png", c.pixel_format)));
        // Values: the pixel on the emitter in each representation of the same XYZ.
        const io::Image image = io::read_image(exr);
        const Vec3 xyz = film.xyz(1, 4);
        const std::string format = c.pixel_format;
        const double tolerance = std::string(c.component_format) == "float16" ? 2e-3 : 1e-6;
        if (format == "rgb" || format == "rgba") {
            const Vec3 rgb = spectrum::xyz_to_linear_srgb(xyz);
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(image.at(1, 4, k), rgb[k], tolerance * std::max(1.0, rgb[k]));
        } else if (format == "luminance" || format == "luminance_alpha") {
            EXPECT_NEAR(image.at(1, 4, 0), xyz.y, tolerance * std::max(1.0, xyz.y));
        }
        if (format.back() == 'a') {
            EXPECT_EQ(image.at(6, 4, 3), 0.0f) << format;  // alpha of an empty pixel
        }
    }
    EXPECT_NE(load_error(R"(<scene version="3.0.0"><sensor type="perspective"><film type="hdrfilm">
        <string name="component_format" value="uint32"/></film></sensor></scene>)").find("uint32 is not supported"),
              std::string::npos);
}
