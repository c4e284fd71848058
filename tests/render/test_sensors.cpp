// The sensors (sensors/*.cpp): Mitsuba's field-of-view conventions (fov_axis, focal_length), focus_distance of a
// pinhole, and the thin lens focusing at focus_distance (geometry of the generated rays, and a rendered point light
// that is sharp on the focal plane and blurred into the predicted circle of confusion off it).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "render_test_util.hpp"

using namespace surfscatter;
using namespace surfscatter::render;
using namespace surfscatter::render::test;

namespace {

std::unique_ptr<Scene> load_sensor(const std::string& sensor_body, int width = 30, int height = 20,
                                   const std::string& type = "perspective") {
    return load_scene_from_string(fmt::format(R"(<scene version="3.0.0"><sensor type="{}">{}
        <film type="hdrfilm"><integer name="width" value="{}"/><integer name="height" value="{}"/></film></sensor></scene>)",
                                              type, sensor_body, width, height),
                                  "sensor.xml");
}

// Half-extents tan(fov_x / 2), tan(fov_y / 2) of a camera, read back through project().
std::pair<double, double> half_tangents(const Scene& scene) {
    const Camera camera(scene.camera, scene.film.width, scene.film.height);
    // The right edge of the image is local -x: the point (-t, 0, 1) projects to x = width when t = tan_x.
    const Ray corner = camera.generate_ray(scene.film.width, scene.film.height);
    const Vec3 local = scene.camera.to_world.inverse().vector(corner.direction);
    return {std::abs(local.x / local.z), std::abs(local.y / local.z)};
}

}  // namespace

TEST(Sensors, FieldOfViewFollowsMitsubasAxes) {
    const double t = std::tan(20 * kDegree);  // fov 40
    const auto check = [&](const std::string& axis, double tx, double ty) {
        const auto scene = load_sensor(R"(<float name="fov" value="40"/><string name="fov_axis" value=")" + axis + R"("/>)");
        const auto [x, y] = half_tangents(*scene);
        EXPECT_NEAR(x, tx, 1e-12) << axis;
        EXPECT_NEAR(y, ty, 1e-12) << axis;
    };
    check("x", t, t * 20 / 30);
    check("y", t * 30 / 20, t);
    check("diagonal", t * 30 / std::hypot(30.0, 20.0), t * 20 / std::hypot(30.0, 20.0));
    check("smaller", t * 30 / 20, t);  // the film is wider than tall: the smaller axis is y
    check("larger", t, t * 20 / 30);
    // focal_length: the 35 mm diagonal (43.27 mm) over twice the focal length; 50mm is the default.
    for (const auto& [body, mm] : {std::pair{std::string(R"(<string name="focal_length" value="28mm"/>)"), 28.0},
                                   std::pair{std::string(""), 50.0}}) {
        const auto scene = load_sensor(body);
        const auto [x, y] = half_tangents(*scene);
        const double diagonal = std::hypot(36.0, 24.0) / (2 * mm);
        EXPECT_NEAR(std::hypot(x, y), diagonal, 1e-12) << body;
        EXPECT_NEAR(x / y, 1.5, 1e-12) << body;
    }
    EXPECT_NE(load_error(R"(<scene version="3.0.0"><sensor type="perspective"><float name="fov" value="40"/>
        <string name="focal_length" value="50mm"/></sensor></scene>)").find("either fov or focal_length"), std::string::npos);
    // A pinhole accepts focus_distance and ignores it (Mitsuba).
    const auto pinhole = load_sensor(R"(<float name="fov" value="40"/><float name="focus_distance" value="3"/>)");
    EXPECT_EQ(pinhole->camera.aperture_radius, 0.0);
}

TEST(Sensors, ThinLensRaysMeetOnTheFocalPlane) {
    const auto scene = load_sensor(R"(<float name="fov" value="30"/><float name="aperture_radius" value="0.2"/>
        <float name="focus_distance" value="4"/>
        <transform name="to_world"><lookat origin="1, 2, 3" target="1, 2, -1" up="0, 1, 0"/></transform>)", 30, 20,
                                   "thinlens");
    const Camera camera(scene->camera, 30, 20);
    const Camera pinhole = [&] {
        CameraSettings s = scene->camera;
        s.aperture_radius = 0;
        return Camera(s, 30, 20);
    }();
    const Transform to_local = scene->camera.to_world.inverse();
    for (const Vec2 pixel : {Vec2(3.2, 4.7), Vec2(15, 10), Vec2(29.5, 0.5)}) {
        const Ray reference = pinhole.generate_ray(pixel.x, pixel.y);
        const Vec3 d = to_local.vector(reference.direction);
        const Vec3 focus = reference.origin + reference.direction * (4 / d.z);  // the pinhole ray at depth 4
        double spread = 0, lens_extent = 0;
        for (const Vec2 u : {Vec2(0.1, 0.2), Vec2(0.9, 0.5), Vec2(0.5, 0.99), Vec2(0.3, 0.7)}) {
            const Ray ray = camera.generate_ray(pixel.x, pixel.y, u);
            const Vec3 o = to_local.point(ray.origin), dir = to_local.vector(ray.direction);
            EXPECT_NEAR(o.z, 0.0, 1e-12);
            lens_extent = std::max(lens_extent, std::hypot(o.x, o.y));
            const Vec3 at_focus = ray.origin + ray.direction * ((4 - o.z) / dir.z);
            spread = std::max(spread, (at_focus - focus).length());
        }
        EXPECT_LT(spread, 1e-12) << pixel.x << "," << pixel.y;
        EXPECT_GT(lens_extent, 0.05);
        EXPECT_LE(lens_extent, 0.2 + 1e-12);
    }
    EXPECT_NE(load_error(R"(<scene version="3.0.0"><sensor type="thinlens"><float name="fov" value="30"/></sensor></scene>)")
                  .find("aperture_radius"), std::string::npos);
}

TEST(Sensors, ThinLensImagesAPointSharpOnlyAtTheFocusDistance) {
    // A small bright disk at depth 4 (facing the camera) seen through a lens focused at 4 stays within its own
    // image; focused at 2 it spreads over the circle of confusion of diameter a (4 - 2) / 2 x (image scale),
    // a = 2 aperture_radius, measured on the plane of the disk: a |z - f| / f = 0.4 at z = 4, f = 2.
    auto render_width = [](double focus) {
        const std::string xml = fmt::format(R"(<scene version="3.0.0">
            <integrator type="path"><integer name="max_depth" value="1"/></integrator>
            <sensor type="thinlens"><float name="fov" value="{}"/><float name="aperture_radius" value="0.2"/>
                <float name="focus_distance" value="{}"/>
                <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
                <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="1"/>
                    <rfilter type="box"/></film></sensor>
            <shape type="disk"><transform name="to_world"><scale value="0.05"/></transform>
                <emitter type="area"><spectrum name="radiance" value="360:1, 830:1"/></emitter></shape>
        </scene>)", 2 * std::atan(0.4 / 4) / kDegree, focus);  // 64 pixels span 0.8 units at depth 4
        const Film film = render_string(xml, 1024);
        // Extent of the lit columns (value above 1 % of the peak), in units on the disk's plane.
        double peak = 0;
        for (int x = 0; x < 64; ++x) peak = std::max(peak, film.xyz(x, 0).y);
        int first = 64, last = -1;
        for (int x = 0; x < 64; ++x)
            if (film.xyz(x, 0).y > 0.01 * peak) first = std::min(first, x), last = std::max(last, x);
        return (last - first + 1) * 0.8 / 64;
    };
    const double sharp = render_width(4), blurred = render_width(2);
    std::printf("[thinlens] lit width on the focal plane %.4f (disk diameter 0.1), focused at 2: %.4f (predicted 0.1 + 0.4)\n",
                sharp, blurred);
    EXPECT_LE(sharp, 0.1 + 2 * 0.8 / 64);
    EXPECT_NEAR(blurred, 0.5, 2 * 0.8 / 64);
}
