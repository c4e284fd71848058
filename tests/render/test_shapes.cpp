// The shapes (shapes/*.cpp): exact intersection, normals and uv of the analytic cylinder, disk and sphere; their
// area sampling against closed-form irradiance (disk, sphere) and against BSDF sampling (cylinder); Mitsuba's
// serialized format written here with zlib (two meshes, versions 3 and 4), big-endian PLY, shared OBJ vertices and
// the angle-weighted normals a mesh without normals gets.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

#include <fmt/format.h>

#include "mesh_files.hpp"
#include "render_test_util.hpp"

using namespace surfscatter;
using namespace surfscatter::render;
using namespace surfscatter::render::test;
namespace fs = std::filesystem;

namespace {

// The scene's only shape hit by a ray.
std::optional<Hit> hit_shape(const std::string& shape, const Vec3& origin, const Vec3& direction) {
    auto scene = load_scene_from_string(scene_xml(shape), "shape.xml");
    return scene->intersect(Ray{origin, normalize(direction), 0.0, 1e30});
}

// A camera 0.5 above the origin of a white diffuse floor looking down at it, under `light`.
MeanY floor_luminance(const std::string& light) {
    const std::string body = R"(<shape type="rectangle"><transform name="to_world"><scale value="50"/></transform>
        <bsdf type="diffuse"><spectrum name="reflectance" value="360:1, 830:1"/></bsdf></shape>)" + light;
    return mean_y_over_seeds(scene_xml(body, "0, 0, 0.5", "0, 0, 0", 0.1, 4,
                                       R"(<integrator type="path"><integer name="max_depth" value="2"/></integrator>)"),
                             256, 8);
}

}  // namespace

TEST(Shapes, CylinderIsExact) {
    // Radius 0.5 around the segment (0, 0, -1) -> (0, 0, 1), moved by +2 in x.
    const std::string cylinder = R"(<shape type="cylinder"><point name="p0" x="0" y="0" z="-1"/><point name="p1" x="0" y="0" z="1"/>
        <float name="radius" value="0.5"/><transform name="to_world"><translate x="2"/></transform></shape>)";
    const auto hit = hit_shape(cylinder, {0, 0.3, 0.2}, {1, 0, 0});
    ASSERT_TRUE(hit);
    const double x = 2 - std::sqrt(0.25 - 0.09);
    EXPECT_NEAR(hit->p.x, x, 1e-12);
    EXPECT_NEAR(hit->t, x, 1e-12);
    EXPECT_NEAR(hit->ng.x, (x - 2) / 0.5, 1e-12);  // outward
    EXPECT_NEAR(hit->ng.y, 0.6, 1e-12);
    EXPECT_NEAR(hit->uv.y, 0.6, 1e-12);  // (z - z0) / length
    EXPECT_FALSE(hit_shape(cylinder, {0, 0, 1.5}, {1, 0, 0}));  // beyond the end: no caps
    // Seen from inside (through the open end), the far wall; flip_normals turns the normal inward.
    const std::string flipped = R"(<shape type="cylinder"><float name="radius" value="0.5"/><boolean name="flip_normals" value="true"/></shape>)";
    const auto inside = hit_shape(flipped, {0, 0, 0.5}, {1, 0, 0});
    ASSERT_TRUE(inside);
    EXPECT_NEAR(inside->p.x, 0.5, 1e-12);
    EXPECT_NEAR(inside->ng.x, -1.0, 1e-12);
}

TEST(Shapes, DiskAndSphereAreExact) {
    const std::string disk = R"(<shape type="disk"><transform name="to_world"><scale x="2" y="1" z="1"/><translate z="1"/></transform></shape>)";
    const auto on = hit_shape(disk, {1.9, 0, 5}, {0, 0, -1});
    ASSERT_TRUE(on);
    EXPECT_NEAR(on->p.z, 1.0, 1e-12);
    EXPECT_NEAR(on->ng.z, 1.0, 1e-12);
    EXPECT_NEAR(on->uv.x, 0.95, 1e-12);  // r in the disk's own frame
    EXPECT_FALSE(hit_shape(disk, {1.9, 0.5, 5}, {0, 0, -1}));  // outside the ellipse x^2/4 + y^2 = 1
    const auto sphere = hit_shape(R"(<shape type="sphere"><point name="center" x="0" y="0" z="1"/><float name="radius" value="0.25"/></shape>)",
                                  {0, 0.1, 5}, {0, 0, -1});
    ASSERT_TRUE(sphere);
    EXPECT_NEAR(sphere->p.z, 1 + std::sqrt(0.0625 - 0.01), 1e-12);
    EXPECT_NEAR(sphere->uv.x, 0.25, 1e-12);  // phi = 90 degrees
}

TEST(Shapes, AreaLightsDeliverTheirClosedFormIrradiance) {
    // Unit radiance (flat spectrum) on a white floor: L = E / pi.
    // A disk of radius R facing down at height h above the viewed point: E = pi R^2 / (R^2 + h^2).
    const std::string disk = R"(<shape type="disk"><transform name="to_world"><scale value="0.4"/><rotate x="1" angle="180"/>
        <translate z="1.5"/></transform><emitter type="area"><spectrum name="radiance" value="360:1, 830:1"/></emitter></shape>)";
    const MeanY lit_by_disk = floor_luminance(disk);
    std::printf("[disk light] %.6f +- %.6f, closed form %.6f\n", lit_by_disk.mean, lit_by_disk.standard_error, 0.16 / 2.41);
    EXPECT_NEAR(lit_by_disk.mean, 0.16 / (0.16 + 2.25), 4 * lit_by_disk.standard_error + 1e-4);
    // A sphere of radius R whose centre is at height d: E = pi (R / d)^2.
    const std::string sphere = R"(<shape type="sphere"><point name="center" x="0" y="0" z="2"/><float name="radius" value="0.3"/>
        <emitter type="area"><spectrum name="radiance" value="360:1, 830:1"/></emitter></shape>)";
    const MeanY lit_by_sphere = floor_luminance(sphere);
    std::printf("[sphere light] %.6f +- %.6f, closed form %.6f\n", lit_by_sphere.mean, lit_by_sphere.standard_error, 0.09 / 4);
    EXPECT_NEAR(lit_by_sphere.mean, 0.09 / 4, 4 * lit_by_sphere.standard_error + 1e-4);
}

TEST(Shapes, CylinderLightSamplingAgreesWithBsdfSampling) {
    double means[3], errors[3];
    int i = 0;
    for (const char* strategy : {"mis", "bsdf", "emitter"}) {
        const std::string body = R"(<shape type="rectangle"><transform name="to_world"><scale value="50"/></transform>
            <bsdf type="diffuse"/></shape>
            <shape type="cylinder"><point name="p0" x="-1" y="0.5" z="0.6"/><point name="p1" x="1" y="0.2" z="0.9"/>
                <float name="radius" value="0.2"/><emitter type="area"><float name="radiance" value="2"/></emitter></shape>)";
        const MeanY y = mean_y_over_seeds(scene_xml(body, "0, -2, 2", "0, 0, 0", 30, 8,
                                                    fmt::format(R"(<integrator type="path"><integer name="max_depth" value="2"/>
                                                        <string name="strategy" value="{}"/></integrator>)", strategy)),
                                          64, 6);
        means[i] = y.mean;
        errors[i++] = y.standard_error;
        std::printf("[cylinder light] %-7s %.5f +- %.5f\n", strategy, y.mean, y.standard_error);
    }
    EXPECT_NEAR(means[0], means[1], 4 * std::hypot(errors[0], errors[1]));
    EXPECT_NEAR(means[0], means[2], 4 * std::hypot(errors[0], errors[2]));
}

TEST(Shapes, SerializedMeshesByShapeIndex) {
    const fs::path dir = temp_dir("test_shapes");
    const std::vector<Vec3> quad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const std::vector<std::array<std::uint32_t, 3>> two = {{0, 1, 2}, {0, 2, 3}};
    for (int version : {3, 4}) {
        // Mesh 0: a triangle, single precision, no normals; mesh 1: a quad in double precision with normals and uv.
        std::vector<std::uint8_t> file = serialized_mesh(version, {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}, {}, {}, {{0, 1, 2}}, false);
        const std::size_t second = file.size();
        const auto mesh1 = serialized_mesh(version, quad, std::vector<Vec3>(4, {0, 0, 1}), {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, two, true);
        file.insert(file.end(), mesh1.begin(), mesh1.end());
        if (version == 4) put(file, std::uint64_t{0}), put(file, static_cast<std::uint64_t>(second));
        else put(file, std::uint32_t{0}), put(file, static_cast<std::uint32_t>(second));
        put(file, std::uint32_t{2});
        const fs::path path = dir / fmt::format("v{}.serialized", version);
        std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(file.data()), static_cast<long>(file.size()));
        bool face_normals = true;
        const TriangleMesh first = load_serialized(path, 0, face_normals);
        EXPECT_FALSE(face_normals);
        ASSERT_EQ(first.triangles.size(), 1u);
        EXPECT_EQ(first.positions[1], Vec3(2, 0, 0));
        EXPECT_TRUE(first.normals.empty());
        const TriangleMesh quad_mesh = load_serialized(path, 1, face_normals);
        ASSERT_EQ(quad_mesh.triangles.size(), 2u);
        EXPECT_EQ(quad_mesh.positions[2], Vec3(1, 1, 0));
        EXPECT_EQ(quad_mesh.uvs[2].x, 1.0);
        EXPECT_EQ(quad_mesh.normals.size(), 4u);
        EXPECT_THROW(load_serialized(path, 2, face_normals), Error);
        // Through the loader: shape_index, to_world and a hit on the quad.
        auto scene = load_scene_from_string(scene_xml(fmt::format(R"(<shape type="serialized"><string name="filename" value="{}"/>
            <integer name="shape_index" value="1"/><transform name="to_world"><translate z="1"/></transform></shape>)",
                                                                  path.filename().string())),
                                            dir / "scene.xml");
        const auto hit = scene->intersect(Ray{{0.5, 0.5, 5}, {0, 0, -1}, 0, 1e30});
        ASSERT_TRUE(hit);
        EXPECT_NEAR(hit->p.z, 1.0, 1e-6);
    }
    std::ofstream(dir / "garbage.serialized") << "not a mesh at all";
    bool unused = false;
    EXPECT_THROW(load_serialized(dir / "garbage.serialized", 0, unused), Error);
}

TEST(Shapes, BigEndianPlyAndSmoothNormals) {
    const fs::path dir = temp_dir("test_shapes_ply");
    {
        std::ofstream out(dir / "be.ply", std::ios::binary);
        out << "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "property float u\nproperty float v\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
        const auto be_float = [&](float f) {
            std::uint32_t bits;
            std::memcpy(&bits, &f, 4);
            for (int shift = 24; shift >= 0; shift -= 8) out.put(static_cast<char>((bits >> shift) & 0xFF));
        };
        const float data[15] = {0, 0, 0, 0, 0, 3, 0, 0, 1, 0, 0, 3, 0, 0, 1};
        for (float f : data) be_float(f);
        out.put(3);
        for (int index : {0, 1, 2})
            for (int shift = 24; shift >= 0; shift -= 8) out.put(static_cast<char>((index >> shift) & 0xFF));
    }
    const TriangleMesh ply = load_ply(dir / "be.ply");
    EXPECT_EQ(ply.positions[1], Vec3(3, 0, 0));
    EXPECT_EQ(ply.uvs[2].y, 1.0);
    // Angle-weighted normals: a corner shared by a right angle in the xy plane (counter-clockwise from +z, normal
    // +z) and a 45-degree angle in the xz plane (counter-clockwise seen from +y, normal +y) gets
    // normalize(pi/2 z + pi/4 y).
    TriangleMesh corner;
    corner.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 1}};
    corner.triangles = {{0, 1, 2}, {0, 3, 1}};
    recompute_vertex_normals(corner);
    const Vec3 expected = normalize(Vec3(0, kPi / 4, kPi / 2));
    EXPECT_NEAR(dot(corner.normals[0], expected), 1.0, 1e-12);
    // An OBJ without vn gets them through the plugin unless face_normals is set.
    std::ofstream(dir / "corner.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 1\nf 1 2 3\nf 1 4 2\n";
    for (const bool faceted : {false, true}) {
        auto scene = load_scene_from_string(scene_xml(fmt::format(R"(<shape type="obj"><string name="filename" value="corner.obj"/>
            <boolean name="face_normals" value="{}"/></shape>)", faceted ? "true" : "false")), dir / "scene.xml");
        const auto hit = scene->intersect(Ray{{0.05, 0.05, 1}, {0, 0, -1}, 0, 1e30});
        ASSERT_TRUE(hit);
        EXPECT_EQ(hit->ns == hit->ng, faceted);
    }
}

// The shading frame's tangent s (docs/RENDERER.md, "Tangent frames"), which orients anisotropic materials: dp/du of
// each shape, continuous over the shape (across the triangles of a mesh, with or without a uv map).
TEST(Shapes, TangentFramesFollowEachShapesParametrisation) {
    const auto tangent = [](const std::string& shape, const Vec3& origin, const Vec3& direction = {0, 0, -1}) {
        const auto hit = hit_shape(shape, origin, direction);
        EXPECT_TRUE(hit) << shape;
        return hit ? hit->shading_frame().s : Vec3();
    };
    const auto expect_along = [](const Vec3& s, const Vec3& expected, const std::string& what) {
        const Vec3 e = normalize(expected);
        EXPECT_NEAR(s.x, e.x, 1e-9) << what;
        EXPECT_NEAR(s.y, e.y, 1e-9) << what;
        EXPECT_NEAR(s.z, e.z, 1e-9) << what;
    };
    // rectangle: s = to_world's x axis, the same on both triangles (either side of the diagonal x = y).
    const std::string rectangle = R"(<shape type="rectangle"><transform name="to_world"><rotate z="1" angle="30"/></transform></shape>)";
    const Vec3 rect_s(std::cos(30 * kDegree), std::sin(30 * kDegree), 0);
    expect_along(tangent(rectangle, {0.3, -0.2, 2}), rect_s, "rectangle, one triangle");
    expect_along(tangent(rectangle, {-0.2, 0.3, 2}), rect_s, "rectangle, the other");
    // cube: each face's s is Frame(face normal).s; the +z face's is x.
    expect_along(tangent(R"(<shape type="cube"/>)", {0.4, -0.3, 3}), {1, 0, 0}, "cube +z face");
    expect_along(tangent(R"(<shape type="cube"/>)", {-0.4, 0.3, 3}), {1, 0, 0}, "cube +z face, other triangle");
    // disk: radial; sphere and cylinder: along their circles of latitude (counter-clockwise about their +z).
    expect_along(tangent(R"(<shape type="disk"/>)", {0.3, 0.4, 2}), {0.3, 0.4, 0}, "disk");
    expect_along(tangent(R"(<shape type="sphere"/>)", {0.3, 0.4, 2}), {-0.4, 0.3, 0}, "sphere");
    expect_along(tangent(R"(<shape type="cylinder"/>)", {3, 0.3, 0.5}, {-1, 0, 0}), {-0.3, std::sqrt(1 - 0.09), 0},
                 "cylinder");
    // Meshes: a square of two triangles whose first edges differ. With a uv map, s = dp/du (here u runs along y);
    // without, Frame(n).s (x for n = +z) on both triangles.
    const fs::path dir = temp_dir("tangent_frames");
    const std::string vertices = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n";
    std::ofstream(dir / "plain.obj") << vertices << "f 1 2 3\nf 3 4 1\n";
    std::ofstream(dir / "uv.obj") << vertices << "vt 0 0\nvt 0 1\nvt 1 1\nvt 1 0\nf 1/1 2/2 3/3\nf 3/3 4/4 1/1\n";
    const auto obj = [&](const char* name) {
        return fmt::format(R"(<shape type="obj"><string name="filename" value="{}"/></shape>)", (dir / name).string());
    };
    expect_along(tangent(obj("plain.obj"), {0.5, -0.5, 2}), {1, 0, 0}, "mesh without uv");
    expect_along(tangent(obj("plain.obj"), {-0.5, 0.5, 2}), {1, 0, 0}, "mesh without uv, other triangle");
    expect_along(tangent(obj("uv.obj"), {0.5, -0.5, 2}), {0, 1, 0}, "mesh with uv");
    expect_along(tangent(obj("uv.obj"), {-0.5, 0.5, 2}), {0, 1, 0}, "mesh with uv, other triangle");
}

// The lay follows the shape's tangent frame: a brushed plate (ggx_stats, elliptical KC) turned by 90 deg about its
// normal renders as the unturned plate with the lay angle 90 deg larger (the square covers itself), and unlike the
// unturned plate at the same lay angle.
TEST(Shapes, LayAngleFollowsTheTangentFrame) {
    const auto plate = [](double turn_deg, double lay_deg) {
        const std::string body = fmt::format(R"(
            <shape type="rectangle"><transform name="to_world"><rotate z="1" angle="{}"/></transform>
              <bsdf type="ggx_stats"><string name="material" value="Al"/><float name="sigma" value="0.1"/>
                <float name="corr_length" value="2"/><float name="corr_length_v" value="0.4"/>
                <float name="lay_angle" value="{}"/><float name="gamma" value="4"/></bsdf></shape>
            <emitter type="point"><point name="position" x="1.5" y="0.7" z="1"/>
              <spectrum name="intensity" value="360:5, 830:5"/></emitter>)", turn_deg, lay_deg);
        return mean_y(render_string(scene_xml(body, "-1, -0.4, 1.2", "0, 0, 0", 60, 16), 16));
    };
    const MeanY turned = plate(90, 20), laid = plate(0, 110), unturned = plate(0, 20);
    EXPECT_NEAR(turned.mean, laid.mean, 1e-6 * laid.mean);
    EXPECT_GT(std::abs(unturned.mean - laid.mean), 0.05 * laid.mean);
}
