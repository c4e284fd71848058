// The emitters (emitters/*.cpp): spot and directional lights against the irradiance they must deliver, Mitsuba's
// float-times-D65 convention, and the environment map: a constant map renders as the constant emitter, its colours
// survive the spectral upsampling, its orientation is Mitsuba's, its sampler passes the chi-square test, and the
// estimator gives the same image whichever strategy reaches it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "bsdf/chi2_harness.hpp"
#include "render_test_util.hpp"
#include "surfscatter/io/image.hpp"
#include "surfscatter/spectrum/cie.hpp"
#include "surfscatter/spectrum/color.hpp"

using namespace surfscatter;
using namespace surfscatter::render;
using namespace surfscatter::render::test;
namespace fs = std::filesystem;

namespace {

// A camera 3 units above the point (x, 0, 0) of a large diffuse plane (reflectance 0.5, spectrally flat), seeing a
// small patch around it.
std::string plane_scene(const std::string& emitter, double x = 0) {
    const std::string body = R"(<shape type="rectangle"><transform name="to_world"><scale value="50"/></transform>
        <bsdf type="diffuse"><spectrum name="reflectance" value="360:0.5, 830:0.5"/></bsdf></shape>)" + emitter;
    return scene_xml(body, fmt::format("{}, 0, 3", x), fmt::format("{}, 0, 0", x), 0.2, 4);
}

// Linear sRGB of a spectrum sampled through `eval` (four wavelengths at a time), by 1 nm quadrature.
Vec3 srgb_of(const std::function<SampledSpectrum(const SampledWavelengths&)>& eval) {
    const spectrum::CieTable& cie = spectrum::cie1931();
    Vec3 xyz;
    double y_white = 0;
    for (double lambda = 360; lambda <= 830; lambda += 4) {
        SampledWavelengths w;
        for (int k = 0; k < 4; ++k) w.lambda[static_cast<std::size_t>(k)] = lambda + k;
        const SampledSpectrum s = eval(w);
        for (int k = 0; k < 4; ++k) {
            if (lambda + k > 830) break;
            xyz += cie.xyz_bar(lambda + k) * s[k];
            y_white += cie.xyz_bar(lambda + k).y;
        }
    }
    return spectrum::xyz_to_linear_srgb(xyz / y_white);
}

void write_map(const fs::path& path, int width, int height, const std::function<Vec3(int, int)>& rgb) {
    io::Image image(width, height, 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const Vec3 c = rgb(x, y);
            for (int k = 0; k < 3; ++k) image.at(x, y, k) = static_cast<float>(c[k]);
        }
    io::write_exr(path, image);
}

}  // namespace

TEST(Emitters, SpotLightIntensityAndLinearFalloff) {
    // Spot 2 units above the plane pointing down, cutoff 20, beam 15 degrees; the camera looks at the plane point at
    // angle theta off the axis: L = rho / pi * I falloff cos(theta) / r^2, falloff 1 inside the beam, linear in the
    // angle to 0 at the cutoff.
    const std::string spot = R"(<emitter type="spot"><spectrum name="intensity" value="360:5, 830:5"/>
        <float name="cutoff_angle" value="20"/><float name="beam_width" value="15"/>
        <transform name="to_world"><lookat origin="0, 0, 2" target="0, 0, 0" up="0, 1, 0"/></transform></emitter>)";
    for (double theta : {0.0, 10.0, 17.5, 19.0, 25.0}) {
        const double x = 2 * std::tan(theta * kDegree), r2 = 4 + x * x;
        const double falloff = theta <= 15 ? 1.0 : theta >= 20 ? 0.0 : (20 - theta) / 5;
        const double expected = 0.5 / kPi * 5 * falloff * std::cos(theta * kDegree) / r2;
        const Film film = render_string(plane_scene(spot, x), 64);
        EXPECT_NEAR(mean_y(film).mean, expected, 0.01 * 0.5 / kPi * 5 / 4 + 1e-4) << theta;
    }
}

TEST(Emitters, DirectionalLightDeliversItsIrradiance) {
    // Light travelling along (sin 60, 0, -cos 60): L = rho / pi * E cos 60.
    const std::string sun = fmt::format(R"(<emitter type="directional"><spectrum name="irradiance" value="360:2, 830:2"/>
        <vector name="direction" x="{}" y="0" z="{}"/></emitter>)", std::sin(60 * kDegree), -std::cos(60 * kDegree));
    const double expected = 0.5 / kPi * 2 * 0.5;
    EXPECT_NEAR(mean_y(render_string(plane_scene(sun), 64)).mean, expected, 1e-3 * expected);
    // to_world instead of direction: light along the transformed +z.
    const std::string turned = R"(<emitter type="directional"><spectrum name="irradiance" value="360:2, 830:2"/>
        <transform name="to_world"><rotate y="1" angle="120"/></transform></emitter>)";
    EXPECT_NEAR(mean_y(render_string(plane_scene(turned), 64)).mean, expected, 1e-3 * expected);
}

TEST(Emitters, ConstantValuesOfEmittersAreTimesD65) {
    // Mitsuba's spectral variants: a <float> radiance of an emitter is that value times D65 (normalised to Y = 1),
    // so a white diffuse plane under a constant sky of 0.8 has Y = 0.8 * 0.5 and the chromaticity of D65.
    const std::string sky = R"(<emitter type="constant"><float name="radiance" value="0.8"/></emitter>)";
    const Film film = render_string(plane_scene(sky), 256);
    EXPECT_NEAR(mean_y(film).mean, 0.4, 0.004);
    const Vec2 xy = spectrum::chromaticity(film.xyz(1, 1));
    EXPECT_NEAR(xy.x, 0.3127, 0.003);
    EXPECT_NEAR(xy.y, 0.3290, 0.003);
}

TEST(Emitters, ConstantEnvironmentMapEqualsTheConstantEmitter) {
    const fs::path dir = temp_dir("test_emitters_constant");
    write_map(dir / "grey.exr", 16, 8, [](int, int) { return Vec3(0.6, 0.6, 0.6); });
    const std::string sphere = R"(<shape type="sphere"><bsdf type="diffuse"><float name="reflectance" value="0.7"/></bsdf></shape>)";
    const std::string with_map = scene_xml(sphere + R"(<emitter type="envmap"><string name="filename" value="grey.exr"/>
        <float name="scale" value="1.5"/></emitter>)", "0, 0, 4", "0, 0, 0", 30, 16);
    const std::string with_constant = scene_xml(sphere + R"(<emitter type="constant"><rgb name="radiance" value="0.9, 0.9, 0.9"/></emitter>)",
                                                "0, 0, 4", "0, 0, 0", 30, 16);
    const fs::path scene_path = dir / "scene.xml";
    auto map_scene = load_scene_from_string(with_map, scene_path);
    auto constant_scene = load_scene_from_string(with_constant, scene_path);
    // Same spectrum in every direction, wavelength by wavelength.
    SampledWavelengths w = SampledWavelengths::sample_visible(0.2);
    for (const Vec3 d : {Vec3(0, 1, 0), Vec3(0.3, -0.5, 0.8), Vec3(-1, 0, 0)}) {
        const SampledSpectrum a = map_scene->environment(normalize(d), w), b = constant_scene->environment(normalize(d), w);
        for (int k = 0; k < 4; ++k) EXPECT_NEAR(a[k], b[k], 1e-6 * b[k]);  // texels are stored in float
    }
    // And the same image (the map's importance sampling against the constant emitter's uniform sampling).
    const MeanY map_y = mean_y_over_seeds_of(*map_scene, 16, 6), constant_y = mean_y_over_seeds_of(*constant_scene, 16, 6);
    std::printf("[envmap] constant map %.5f +- %.5f, constant emitter %.5f +- %.5f\n", map_y.mean, map_y.standard_error,
                constant_y.mean, constant_y.standard_error);
    EXPECT_NEAR(map_y.mean, constant_y.mean, 4 * std::hypot(map_y.standard_error, constant_y.standard_error));
}

TEST(Emitters, EnvironmentMapColoursOrientationAndSampling) {
    const fs::path dir = temp_dir("test_emitters_map");
    // Row 0 (the +y pole) red, the last row blue, a bright saturated green spot at column 5 of row 3.
    const int width = 24, height = 9;
    const auto colour = [](int x, int y) {
        if (y == 0) return Vec3(0.8, 0.05, 0.02);
        if (y == height - 1) return Vec3(0.02, 0.1, 0.9);
        if (x == 5 && y == 3) return Vec3(4.0, 30.0, 2.0);
        return Vec3(0.2 + 0.02 * x, 0.3, 0.1 + 0.05 * y);
    };
    write_map(dir / "sky.exr", width, height, colour);
    const std::string xml = scene_xml(R"(<shape type="rectangle"><transform name="to_world"><scale value="20"/></transform>
        <bsdf type="diffuse"/></shape><emitter type="envmap"><string name="filename" value="sky.exr"/></emitter>)",
                                      "0, 0, 3", "0, 0, 0", 40, 8);
    auto scene = load_scene_from_string(xml, dir / "scene.xml");
    // Texel (x, y) sits at phi = 2 pi (x + 1/2) / width, theta = pi y / (height - 1) (Mitsuba's convention);
    // its colour comes back through the spectral upsampling within 5e-3 of the largest channel (the bilinear
    // table of sigmoid coefficients; the saturated green texel is the worst case).
    const auto texel_direction = [&](int x, int y) {
        const double phi = kTwoPi * (x + 0.5) / width, theta = kPi * y / (height - 1);
        return Vec3(std::sin(phi) * std::sin(theta), std::cos(theta), -std::cos(phi) * std::sin(theta));
    };
    double worst = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; x += 5) {
            const Vec3 expected = colour(x, y);
            const Vec3 got = srgb_of([&](const SampledWavelengths& w) { return scene->environment(texel_direction(x, y), w); });
            const double peak = std::max({expected.x, expected.y, expected.z});
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(got[c] - expected[c]) / peak);
        }
    std::printf("[envmap] worst RGB round trip through the sigmoid table: %.2e of the largest channel\n", worst);
    EXPECT_LT(worst, 5e-3);
    const Vec3 up = srgb_of([&](const SampledWavelengths& w) { return scene->environment({0, 1, 0}, w); });
    EXPECT_NEAR(up.x, 0.8, 2e-3);  // +y is the first row

    // Chi-square of the direction sampler against environment_pdf over the whole sphere. The map is turned so that
    // its pole is +z, the histogram's axis: the bins (4.5 x 7.5 degrees) then nest inside the map's cells (22.5 x 15
    // degrees, columns offset by half a texel), where the density is constant per solid angle.
    auto turned = load_scene_from_string(scene_xml(R"(<emitter type="envmap"><string name="filename" value="sky.exr"/>
        <transform name="to_world"><rotate x="1" angle="90"/></transform></emitter>)"), dir / "scene.xml");
    surfscatter::bsdf::test::Chi2Subject subject;
    subject.full_sphere = true;
    const SampledWavelengths w = SampledWavelengths::sample_visible(0.5);
    subject.sample = [&](double ul, Vec2 u) -> std::optional<surfscatter::bsdf::test::DirectionSample> {
        const auto s = turned->sample_emitter({0, 0, 0}, ul, u, w);
        if (!s) return std::nullopt;
        return surfscatter::bsdf::test::DirectionSample{s->wi, s->pdf, 0.0, false};
    };
    subject.pdf = [&](const Vec3& d) { return turned->environment_pdf(d); };
    const auto r = surfscatter::bsdf::test::chi2_test(subject, 400000, 40, 48);
    std::printf("[chi2] envmap sampler %s\n", r.summary().c_str());
    EXPECT_GT(r.p_value, 0.01);
    EXPECT_LT(r.pdf_mismatch, 1e-9);
    EXPECT_NEAR(r.expected_total, 1.0, 1e-3);

    // The three strategies of the path integrator agree on the lit plane (the map's density is right).
    double means[3], errors[3];
    int i = 0;
    for (const char* strategy : {"mis", "bsdf", "emitter"}) {
        const std::string s = scene_xml(R"(<shape type="rectangle"><transform name="to_world"><scale value="20"/></transform>
            <bsdf type="diffuse"/></shape><emitter type="envmap"><string name="filename" value="sky.exr"/></emitter>)",
                                        "0, 0, 3", "0, 0, 0", 40, 8,
                                        fmt::format(R"(<integrator type="path"><integer name="max_depth" value="2"/>
                                            <string name="strategy" value="{}"/></integrator>)", strategy));
        auto strategy_scene = load_scene_from_string(s, dir / "scene.xml");
        const MeanY y = mean_y_over_seeds_of(*strategy_scene, 32, 6);
        means[i] = y.mean;
        errors[i++] = y.standard_error;
        std::printf("[envmap] strategy %-7s %.5f +- %.5f\n", strategy, y.mean, y.standard_error);
    }
    EXPECT_NEAR(means[0], means[1], 4 * std::hypot(errors[0], errors[1]));
    EXPECT_NEAR(means[0], means[2], 4 * std::hypot(errors[0], errors[2]));
}
