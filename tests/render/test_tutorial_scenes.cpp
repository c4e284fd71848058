// Mitsuba 3's tutorial scenes (mitsuba-renderer/mitsuba-tutorials, scenes/) as users have them: the Cornell box
// rebuilt from its published files and rendered without edits; simple.xml and the opening of lego/scene.xml with
// stand-ins for their binary meshes and environment (not retrievable here), to show that their XML loads unedited.
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

TEST(TutorialScenes, SimpleXmlLoadsAndRendersUnedited) {
    // scenes/simple.xml (version 3.0.0, commit d0d6d6c7f45c): the direct integrator, a PLY teapot (here a stand-in
    // tetrahedron), point lights with single-valued <rgb> intensities, space-separated <rgb> values.
    const fs::path dir = temp_dir("simple");
    fs::create_directories(dir / "meshes");
    std::ofstream(dir / "meshes" / "teapot.ply") << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
        "property float y\nproperty float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
        "-1 -1 0\n1 -1 0\n0 1 0\n0 0 2.5\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n";
    std::ofstream(dir / "simple.xml") << R"(<scene version='3.0.0'>
    <default name="spp" value="256"/>
    <default name="res" value="256"/>

    <integrator type='direct'/>

    <sensor type="perspective" id="sensor">
        <transform name="to_world">
            <lookat target="0.0, 0.0, 1.25"
                    origin="0.0, -12.0, 5.0"
                    up    ="0.0, 0.0, 1.0"/>
        </transform>
        <sampler type="independent">
            <integer name="sample_count" value="$spp"/>
        </sampler>
        <film type="hdrfilm">
            <rfilter type="box"/>
            <integer name="width"  value="$res"/>
            <integer name="height" value="$res"/>
        </film>
    </sensor>

    <shape type="ply" id="teapot">
        <string name="filename" value="meshes/teapot.ply"/>
        <bsdf type="diffuse">
            <rgb name="reflectance" value="0.9 0.9 0.0"/>
        </bsdf>
    </shape>

    <emitter type="point" id="light1">
        <point name="position" x="3" y="-10.0" z="6.0"/>
        <rgb name="intensity" value="100.0"/>
    </emitter>

    <emitter type="point" id="light2">
        <point name="position" x="-3" y="-10.0" z="-2.0"/>
        <rgb name="intensity" value="100.0"/>
    </emitter>
</scene>
)";
    auto scene = load_scene(dir / "simple.xml", {{"res", "32"}, {"spp", "8"}});
    EXPECT_EQ(scene->integrator.type, "direct");
    RenderOptions options;
    options.progress = false;
    const Film film = surfscatter::render::render(*scene, options);
    const Vec3 centre = spectrum::xyz_to_linear_srgb(film.xyz(16, 18));
    EXPECT_GT(centre.x, 5 * centre.z) << "the yellow teapot stand-in is lit";
}

TEST(TutorialScenes, LegoSceneOpeningLoadsUnedited) {
    // The first elements of scenes/lego/scene.xml (commit fba2eb0884202): path with hide_emitters, a rotated envmap
    // (here a stand-in .hdr), a BSDF with a volume texture that nothing references (built lazily, so never), twosided
    // diffuse materials, and PLY shapes referring to them by <ref id="..." name="bsdf"/> (stand-in meshes).
    const fs::path dir = temp_dir("lego");
    fs::create_directories(dir / "meshes");
    fs::create_directories(dir / "textures");
    std::string texels;
    for (int i = 0; i < 24; ++i) texels += "\x80\x80\x80\x7F";  // flat RGBE, 0.25 everywhere
    std::ofstream(dir / "textures" / "cathedral.hdr", std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 6\n" << texels;
    for (const char* mesh : {"PinTransitionConnector_01_02_002.ply", "Brick_flat_01_02_black_007.ply"})
        std::ofstream(dir / "meshes" / mesh) << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    std::ofstream(dir / "scene.xml") << R"(<scene version="3.0.0">

<!-- Defaults, these can be set via the command line: -Darg=value -->

	<default name="spp" value="64"/>
	<default name="resx" value="512"/>
	<default name="resy" value="512"/>
	<default name="max_depth" value="8"/>
	<default name="pixel_format" value="rgb"/>

<!-- Camera and Rendering Parameters -->

	<integrator type="path">
		<integer name="max_depth" value="$max_depth"/>
		<boolean name="hide_emitters" value="true"/>
	</integrator>

	<sensor type="perspective">
		<float name="fov" value="39"/>
		<transform name="to_world">
			<lookat origin="-1.2, 0.5, 1.2"
                    target="0.4, 0.45, 0.5"
                    up="0, 1, 0"/>
		</transform>

		<sampler type="independent">
		    <integer name="sample_count" value="$spp"/>
        </sampler>

        <film type="hdrfilm">
            <integer name="width" value="$resx"/>
            <integer name="height" value="$resy"/>
            <string name="pixel_format" value="$pixel_format"/>
            <rfilter type="gaussian"/>
        </film>
	</sensor>

	<emitter type="envmap">
		<string name="filename" value="textures/cathedral.hdr" />
		<float name="scale" value="0.5"/>
        <transform name="to_world">
            <rotate x="0.0" y="1.0" z="0.0" angle="20"/>
        </transform>
	</emitter>

<!-- Materials -->

	<bsdf type="diffuse"  id="main-bsdf">
        <texture type="volume" name="reflectance">
            <volume type="gridvolume" name="volume">
                <string name="filename" value="textures/red.vol"/>
            </volume>
        </texture>
	</bsdf>

	<bsdf type="twosided" id="mat-Gray">
		<bsdf type="diffuse">
			<rgb value="0.296138 0.323143 0.391572" name="reflectance"/>
		</bsdf>
	</bsdf>
	<bsdf type="twosided" id="mat-Black">
		<bsdf type="diffuse">
			<rgb value="0.002808 0.002808 0.002808" name="reflectance"/>
		</bsdf>
	</bsdf>

	<shape type="ply">
		<string name="filename" value="meshes/PinTransitionConnector_01_02_002.ply"/>
		<ref id="mat-Gray" name="bsdf"/>
	</shape>
	<shape type="ply">
		<string name="filename" value="meshes/Brick_flat_01_02_black_007.ply"/>
		<ref id="mat-Black" name="bsdf"/>
	</shape>
</scene>
)";
    auto scene = load_scene(dir / "scene.xml", {{"resx", "16"}, {"resy", "16"}, {"spp", "2"}});
    EXPECT_TRUE(scene->integrator.hide_emitters);
    EXPECT_TRUE(scene->has_environment());
    // Nothing refers to the volume-textured BSDF: it is built all the same, and its texture, a plugin of Mitsuba's
    // that surfscatter lacks, becomes a note naming both elements instead of an error.
    const auto note = std::find_if(scene->notes.begin(), scene->notes.end(), [](const std::string& n) {
        return n.find("is referenced by nothing and not built") != std::string::npos;
    });
    ASSERT_NE(note, scene->notes.end());
    EXPECT_NE(note->find("scene.xml:48: <bsdf id=\"main-bsdf\">"), std::string::npos) << *note;
    EXPECT_NE(note->find("scene.xml:49: unknown texture plugin 'volume'"), std::string::npos) << *note;
    // Referring to the volume-textured BSDF builds it where it is referenced, and then its plugin is an error.
    const std::string with_ref = R"(<scene version="3.0.0"><sensor type="perspective"/>
        <bsdf type="diffuse" id="main-bsdf"><texture type="volume" name="reflectance"/></bsdf>
        <shape type="cube"><ref id="main-bsdf"/></shape></scene>)";
    EXPECT_NE(load_error(with_ref).find("scene.xml:2: unknown texture plugin 'volume'"), std::string::npos) << load_error(with_ref);
}
