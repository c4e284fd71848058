// Closed-form checks of the path tracer (issue 5 "Done when"): each compares the film's luminance Y with a value
// computed independently. A spectrally constant radiance of 1 has Y = 1 by the film's normalisation.
#include <gtest/gtest.h>

#include <cmath>

#include <fmt/format.h>

#include "render_test_util.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/material/fresnel.hpp"
#include "surfscatter/spectrum/cie.hpp"

using namespace surfscatter;
using namespace surfscatter::render;
using namespace surfscatter::render::test;

TEST(RenderAnalytic, DiffusePlaneUnderPointLight) {
    // rho / pi * I cos(theta) / d^2 at the point the camera looks at: light at (0.5, 0, 1) above the origin.
    const std::string body = R"(
        <shape type="rectangle"><transform name="to_world"><scale value="10"/></transform>
            <bsdf type="diffuse"><float name="reflectance" value="0.5"/></bsdf></shape>
        <emitter type="point"><point name="position" x="0.5" y="0" z="1"/><float name="intensity" value="3"/></emitter>)";
    const Film film = render_string(scene_xml(body, "0, 0, 3", "0, 0, 0", 0.2), 256);
    const double d2 = 1.25, cos_theta = 1 / std::sqrt(1.25);
    const double expected = 0.5 / kPi * 3 * cos_theta / d2;
    const MeanY y = mean_y(film);
    EXPECT_NEAR(y.mean, expected, 0.01 * expected) << "standard error " << y.standard_error;
}

TEST(RenderAnalytic, SmoothConductorReflectsUniformEmitter) {
    // A constant environment of radiance 1 seen in a smooth conductor at 60 degrees: L = R(60 deg) (eta, k constant).
    const std::string body = R"(
        <shape type="rectangle"><transform name="to_world"><scale value="100"/></transform>
            <bsdf type="conductor"><float name="eta" value="0.2"/><float name="k" value="3"/></bsdf></shape>
        <emitter type="constant"><float name="radiance" value="1"/></emitter>)";
    const double theta = 60 * kDegree;
    const std::string origin = fmt::format("{}, 0, {}", 3 * std::sin(theta), 3 * std::cos(theta));
    const Film film = render_string(scene_xml(body, origin, "0, 0, 0", 0.5), 128);
    const double expected = material::fresnel_conductor(std::cos(theta), {0.2, 3.0});
    const MeanY y = mean_y(film);
    EXPECT_NEAR(y.mean, expected, 0.01 * expected) << "standard error " << y.standard_error;
}

TEST(RenderAnalytic, WhiteFurnace) {
    // An albedo-1 diffuse sphere in a constant environment is invisible: every pixel returns the environment.
    const std::string body = R"(
        <shape type="sphere"><float name="radius" value="1"/>
            <bsdf type="diffuse"><float name="reflectance" value="1"/></bsdf></shape>
        <emitter type="constant"><float name="radiance" value="0.7"/></emitter>)";
    const Film film = render_string(scene_xml(body, "0, 0, 4", "0, 0, 0", 30, 16), 64);
    const MeanY y = mean_y(film);
    EXPECT_NEAR(y.mean, 0.7, 0.007) << "standard error " << y.standard_error;
    // The pixels on the sphere alone (centre 6x6 block), where MIS of both strategies matters.
    double sum = 0;
    for (int py = 5; py < 11; ++py)
        for (int px = 5; px < 11; ++px) sum += film.xyz(px, py).y;
    EXPECT_NEAR(sum / 36, 0.7, 0.007);
}

TEST(RenderAnalytic, BsdfSamplingAndEmitterSamplingAgree) {
    // A diffuse plane under a small area light: BSDF sampling only, emitter sampling only and MIS must agree.
    const std::string body = R"(
        <shape type="rectangle"><transform name="to_world"><scale value="3"/></transform>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.4, 0.2"/></bsdf></shape>
        <shape type="rectangle">
            <transform name="to_world"><scale value="0.3"/><rotate x="1" angle="180"/><translate z="1"/></transform>
            <emitter type="area"><spectrum name="radiance" type="blackbody"><float name="temperature" value="4000"/>
                <float name="scale" value="0.01"/></spectrum></emitter></shape>)";
    auto with = [&](const char* strategy) {
        const std::string integrator =
            std::string("<integrator type=\"path\"><integer name=\"max_depth\" value=\"3\"/><string name=\"strategy\" value=\"") +
            strategy + "\"/></integrator>";
        return mean_y_over_seeds(scene_xml(body, "0, -2, 2", "0, 0, 0", 40, 16, integrator), 32, 8);
    };
    const MeanY mis = with("mis"), bsdf = with("bsdf"), emitter = with("emitter");
    const double tolerance_b = 4 * std::hypot(mis.standard_error, bsdf.standard_error);
    const double tolerance_e = 4 * std::hypot(mis.standard_error, emitter.standard_error);
    EXPECT_GT(mis.mean, 0);
    EXPECT_NEAR(bsdf.mean, mis.mean, tolerance_b);
    EXPECT_NEAR(emitter.mean, mis.mean, tolerance_e);
    EXPECT_LT(mis.standard_error, bsdf.standard_error);  // MIS is the point of the exercise
}

TEST(RenderDeterminism, SameImageForOneAndTwoThreads) {
    const std::string body = R"(
        <shape type="rectangle"><transform name="to_world"><scale value="3"/></transform>
            <bsdf type="diffuse"><texture name="reflectance" type="checkerboard">
                <transform name="to_uv"><scale value="4"/></transform></texture></bsdf></shape>
        <shape type="sphere"><point name="center" x="0" y="0" z="0.5"/><float name="radius" value="0.5"/>
            <bsdf type="conductor"><string name="material" value="perfect"/></bsdf></shape>
        <emitter type="point"><point name="position" x="0.5" y="1" z="2"/><float name="intensity" value="3"/></emitter>
        <emitter type="constant"><float name="radiance" value="0.1"/></emitter>)";
    const std::string xml = scene_xml(body, "0, -3, 2", "0, 0, 0", 40, 24);
    const Film one = render_string(xml, 8, 1, 7);
    const Film two = render_string(xml, 8, 2, 7);
    const Film other_seed = render_string(xml, 8, 2, 8);
    bool differs = false;
    for (int y = 0; y < one.height(); ++y)
        for (int x = 0; x < one.width(); ++x) {
            ASSERT_EQ(one.xyz(x, y), two.xyz(x, y)) << x << "," << y;
            differs |= !(one.xyz(x, y) == other_seed.xyz(x, y));
        }
    EXPECT_TRUE(differs);
}

TEST(RenderDeterminism, CropWindowReproducesThePixelsOfTheFullFilm) {
    const std::string body = R"(
        <shape type="rectangle"><transform name="to_world"><scale value="3"/></transform>
            <bsdf type="diffuse"><texture name="reflectance" type="checkerboard"/></bsdf></shape>
        <emitter type="constant"><float name="radiance" value="1"/></emitter>)";
    const std::string xml = scene_xml(body, "0, -3, 2", "0, 0, 0", 40, 20);
    auto scene = load_scene_from_string(xml, "test.xml");
    RenderOptions options;
    options.spp = 4;
    options.progress = false;
    const Film full = surfscatter::render::render(*scene, options);
    scene->film.crop_offset_x = 5;
    scene->film.crop_offset_y = 7;
    scene->film.crop_width = 9;
    scene->film.crop_height = 4;
    const Film crop = surfscatter::render::render(*scene, options);
    ASSERT_EQ(crop.width(), 9);
    ASSERT_EQ(crop.height(), 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 9; ++x) ASSERT_EQ(crop.xyz(x, y), full.xyz(x + 5, y + 7));
    scene->film.crop_width = 30;
    EXPECT_THROW(surfscatter::render::render(*scene, options), surfscatter::Error);
}
