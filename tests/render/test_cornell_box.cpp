// Mitsuba 3's tutorial Cornell box, rebuilt here from its published files and rendered without edits.
//
// Source: mitsuba-renderer/mitsuba-tutorials, scenes/cbox.xml (version 3.0.0, commit facfcd3a6343) and
// scenes/meshes/cbox_*.obj (commit d0d6d6c7f45c); the repository ships no licence file (Mitsuba 3 itself is
// BSD-3-Clause). The scene file is reproduced as published for interoperability testing; the meshes are six
// axis-aligned unit quads, written below from their vertex lists.
//
// Orientation. The camera sits at (0, 0, 4) looking toward -z with up +y. Mitsuba's look_at puts the camera's local
// +x along cross(up, dir) = -x of the world, and its perspective projection maps local +x to the left of the image
// (sample x = 0). So world -x is on the image's left: the green wall (x = -1 in cbox_greenwall.obj) is on the left
// and the red wall (x = +1) on the right in this file. Mitsuba's built-in mi.cornell_box() puts the red wall at
// x = -1 instead, and so shows it on the left; its layout is rendered second as a check of the same convention.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "render_test_util.hpp"
#include "surfscatter/spectrum/color.hpp"

using namespace surfscatter;
using namespace surfscatter::render;
using namespace surfscatter::render::test;
namespace fs = std::filesystem;

namespace {

const char* kCboxXml = R"(<scene version="3.0.0">
    <default name="spp" value="128"/>
    <default name="res" value="256"/>
    <default name="max_depth" value="6"/>
    <default name="integrator" value="path"/>

    <integrator type='$integrator'>
        <integer name="max_depth" value="$max_depth"/>
    </integrator>

    <sensor type="perspective" id="sensor">
        <string name="fov_axis" value="smaller"/>
        <float name="near_clip" value="0.001"/>
        <float name="far_clip" value="100.0"/>
        <float name="focus_distance" value="1000"/>
        <float name="fov" value="39.3077"/>
        <transform name="to_world">
            <lookat origin="0,  0,  4"
                    target="0,  0,  0"
                    up    ="0,  1,  0"/>
        </transform>
        <sampler type="independent">
            <integer name="sample_count" value="$spp"/>
        </sampler>
        <film type="hdrfilm">
            <integer name="width"  value="$res"/>
            <integer name="height" value="$res"/>
            <rfilter type="tent"/>
            <string name="pixel_format" value="rgb"/>
            <string name="component_format" value="float32"/>
        </film>
    </sensor>

    <!-- BSDFs -->

    <bsdf type="diffuse" id="gray">
        <rgb name="reflectance" value="0.85, 0.85, 0.85"/>
    </bsdf>

    <bsdf type="diffuse" id="white">
        <rgb name="reflectance" value="0.885809, 0.698859, 0.666422"/>
    </bsdf>

    <bsdf type="diffuse" id="green">
        <rgb name="reflectance" value="0.105421, 0.37798, 0.076425"/>
    </bsdf>

    <bsdf type="diffuse" id="red">
        <rgb name="reflectance" value="0.570068, 0.0430135, 0.0443706"/>
    </bsdf>

    <bsdf type="dielectric" id="glass"/>

    <bsdf type="conductor" id="mirror"/>

    <!-- Light -->

    <shape type="obj" id="light">
        <string name="filename" value="meshes/cbox_luminaire.obj"/>
        <transform name="to_world">
            <translate x="0" y="-0.01" z="0"/>
        </transform>
        <ref id="white"/>
        <emitter type="area">
            <rgb name="radiance" value="18.387, 13.9873, 6.75357"/>
        </emitter>
    </shape>

    <!-- Shapes -->

    <shape type="obj" id="floor">
        <string name="filename" value="meshes/cbox_floor.obj"/>
        <ref id="white"/>
    </shape>

    <shape type="obj" id="ceiling">
        <string name="filename" value="meshes/cbox_ceiling.obj"/>
        <ref id="white"/>
    </shape>

    <shape type="obj" id="back">
        <string name="filename" value="meshes/cbox_back.obj"/>
        <ref id="white"/>
    </shape>

    <shape type="obj" id="greenwall">
        <string name="filename" value="meshes/cbox_greenwall.obj"/>
        <ref id="green"/>
    </shape>

    <shape type="obj" id="redwall">
        <string name="filename" value="meshes/cbox_redwall.obj"/>
        <ref id="red"/>
    </shape>

    <shape type="sphere" id="mirrorsphere">
        <transform name="to_world">
            <scale value="0.5"/>
            <translate x="-0.3" y="-0.5" z="0.2"/>
        </transform>
        <ref id="mirror"/>
    </shape>

    <shape type="sphere" id="glasssphere">
        <transform name="to_world">
            <scale value="0.25"/>
            <translate x="0.5" y="-0.75" z="-0.2"/>
        </transform>
        <ref id="glass"/>
    </shape>
</scene>
)";

// The vertex lists of the tutorial's meshes (each one quad, f 1 2 3 4).
const std::pair<const char*, const char*> kMeshes[] = {
    {"cbox_back.obj", "v  1 -1 -1\nv  1  1 -1\nv -1  1 -1\nv -1 -1 -1\n"},
    {"cbox_ceiling.obj", "v  1  1 -1\nv  1  1  1\nv -1  1  1\nv -1  1 -1\n"},
    {"cbox_floor.obj", "v -1 -1  1\nv  1 -1  1\nv  1 -1 -1\nv -1 -1 -1\n"},
    {"cbox_greenwall.obj", "v -1  1 -1\nv -1  1  1\nv -1 -1  1\nv -1 -1 -1\n"},
    {"cbox_redwall.obj", "v 1 -1  1\nv 1  1  1\nv 1  1 -1\nv 1 -1 -1\n"},
    {"cbox_luminaire.obj", "v  0.25  1 -0.25\nv  0.25  1  0.25\nv -0.25  1  0.25\nv -0.25  1 -0.25\n"},
};

// Mean linear sRGB over columns [x0, x1) and the middle third of the rows.
Vec3 mean_rgb(const Film& film, int x0, int x1) {
    Vec3 sum;
    int n = 0;
    for (int y = film.height() / 3; y < 2 * film.height() / 3; ++y)
        for (int x = x0; x < x1; ++x, ++n) sum += spectrum::xyz_to_linear_srgb(film.xyz(x, y));
    return sum / n;
}

}  // namespace

TEST(CornellBox, MitsubaTutorialSceneRendersWithItsWallsWhereMitsubaPutsThem) {
    const fs::path dir = temp_dir("cbox");
    fs::create_directories(dir / "meshes");
    std::ofstream(dir / "cbox.xml") << kCboxXml;
    for (const auto& [name, vertices] : kMeshes) std::ofstream(dir / "meshes" / name) << vertices << "f 1 2 3 4\n";
    auto scene = load_scene(dir / "cbox.xml", {{"res", "48"}, {"spp", "64"}});
    EXPECT_EQ(scene->film.filter->name(), "tent");
    EXPECT_EQ(scene->film.component_format, "float32");
    RenderOptions options;
    options.progress = false;
    const Film film = surfscatter::render::render(*scene, options);
    write_film(film, scene->film, dir / "cbox.exr");  // and cbox.png, to look at
    const Vec3 left = mean_rgb(film, 0, 4), right = mean_rgb(film, 44, 48);
    std::printf("[cbox] left wall rgb (%.3f, %.3f, %.3f), right wall rgb (%.3f, %.3f, %.3f); image %s\n", left.x, left.y,
                left.z, right.x, right.y, right.z, (dir / "cbox.png").c_str());
    // The walls take colour from a warm light and from each other: the green one is green, not green alone.
    EXPECT_GT(left.y, 1.5 * left.x) << "green wall on the left";
    EXPECT_GT(left.y, 5 * left.z);
    EXPECT_GT(right.x, 3 * right.y) << "red wall on the right";
    // The luminaire (y = 0.99 at depth 4, image row ~7 of 48) is far brighter than the walls.
    double luminaire = 0;
    for (int y = 4; y < 11; ++y) luminaire = std::max(luminaire, film.xyz(24, y).y);
    EXPECT_GT(luminaire, 20 * left.y);
}

TEST(CornellBox, MitsubasBuiltInLayoutShowsRedOnTheLeft) {
    // The walls of Mitsuba's mi.cornell_box(): unit rectangles, red at x = -1 facing +x, green at x = +1 facing -x.
    const std::string body = R"(
        <bsdf type="diffuse" id="white"><rgb name="reflectance" value="0.885809, 0.698859, 0.666422"/></bsdf>
        <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><translate y="-1"/></transform><ref id="white"/></shape>
        <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="90"/><translate y="1"/></transform><ref id="white"/></shape>
        <shape type="rectangle"><transform name="to_world"><translate z="-1"/></transform><ref id="white"/></shape>
        <shape type="rectangle"><transform name="to_world"><rotate y="1" angle="-90"/><translate x="1"/></transform>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.105421, 0.37798, 0.076425"/></bsdf></shape>
        <shape type="rectangle"><transform name="to_world"><rotate y="1" angle="90"/><translate x="-1"/></transform>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.570068, 0.0430135, 0.0443706"/></bsdf></shape>
        <shape type="rectangle"><transform name="to_world"><scale x="0.23" y="0.19" z="0.19"/><rotate x="1" angle="90"/>
            <translate y="0.99" z="0.01"/></transform><emitter type="area"><rgb name="radiance" value="18.387, 13.9873, 6.75357"/></emitter></shape>)";
    const Film film = render_string(scene_xml(body, "0, 0, 3.9", "0, 0, 0", 39.3077, 32), 32);
    const Vec3 left = mean_rgb(film, 0, 3), right = mean_rgb(film, 29, 32);
    EXPECT_GT(left.x, 3 * left.y) << "red wall on the left";
    EXPECT_GT(right.y, 1.5 * right.x) << "green wall on the right";
}
