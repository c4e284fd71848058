// The `measured` plugin (render/bsdfs/measured.cpp) in a furnace: a real RGL file (white paper, RGL's database) on a
// large plane under a constant sky of radiance 1, seen at 60 degrees. One bounce renders the Y-weighted spectral
// mean of int f(light, viewer) cos(theta_light) d light, computed here by quadrature of the file's BSDF
// (tests/bsdf/disc_albedo.hpp): the render checks the plugin's sampling, densities and weights through the
// renderer's MIS and BSDF-only strategies.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "../bsdf/disc_albedo.hpp"
#include "render_test_util.hpp"
#include "surfscatter/bsdf/rgl_measured.hpp"
#include "surfscatter/spectrum/cie.hpp"

using namespace surfscatter;
using namespace surfscatter::render;
using namespace surfscatter::render::test;

TEST(Measured, RealRglFileRendersItsAlbedo) {
    const std::filesystem::path file =
        std::filesystem::path(SURFSCATTER_SHARED_DATA) / "realdata" / "rgl" / "paper_white_rgb.bsdf";
    const bsdf::RglMeasuredBsdf model(bsdf::read_rgl(file));
    const double theta = 60 * kDegree;
    const Vec3 viewer = spherical_direction(theta, 0.0);
    double sum = 0, weight = 0;
    for (double lambda = 370; lambda <= 830; lambda += 20) {
        const double ybar = spectrum::cie1931().xyz_bar(lambda).y;
        sum += ybar * bsdf::test::disc_albedo(model, viewer, lambda);  // the table direction is the viewer's
        weight += ybar;
    }
    const double expected = sum / weight;
    for (const char* strategy : {"mis", "bsdf"}) {
        const std::string body = fmt::format(R"(
            <shape type="rectangle"><transform name="to_world"><scale value="100"/></transform>
                <bsdf type="measured"><string name="filename" value="{}"/></bsdf></shape>
            <emitter type="constant"><float name="radiance" value="1"/></emitter>)", file.string());
        const std::string origin = fmt::format("{}, 0, {}", 3 * std::sin(theta), 3 * std::cos(theta));
        const std::string integrator =
            fmt::format(R"(<integrator type="path"><integer name="max_depth" value="2"/><string name="strategy" value="{}"/></integrator>)", strategy);
        const MeanY y = mean_y(render_string(scene_xml(body, origin, "0, 0, 0", 0.5, 8, integrator), 256));
        std::printf("measured paper furnace %s: %.5f +- %.5f (expected %.5f)\n", strategy, y.mean, y.standard_error,
                    expected);
        EXPECT_NEAR(y.mean, expected, std::max(4 * y.standard_error, 0.01 * expected)) << strategy;
    }
}
