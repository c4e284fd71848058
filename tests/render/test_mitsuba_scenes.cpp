// Mitsuba 3 scenes as users have them: scene versions, .spd spectra, named indices of refraction and metals, errors
// with file:line for every plugin outside the supported set, and small scenes written here that use every
// supported plugin (meshes, textures, environment maps and spectra written beside them).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "mesh_files.hpp"
#include "render_test_util.hpp"
#include "surfscatter/io/image.hpp"

using namespace surfscatter;
using namespace surfscatter::render;
using namespace surfscatter::render::test;
namespace fs = std::filesystem;

namespace {

std::string with_version(const std::string& version, const std::string& body = "") {
    return "<scene version=\"" + version + "\"><sensor type=\"perspective\"/>" + body + "</scene>";
}

}  // namespace

TEST(MitsubaScenes, VersionsOfMitsuba2And3) {
    EXPECT_EQ(load_error(with_version("2.0.0")), "");
    EXPECT_EQ(load_error(with_version("3.5.2")), "");
    EXPECT_NE(load_error(with_version("0.6.0")).find("version 0.6.0 is not supported"), std::string::npos);
    EXPECT_NE(load_error(with_version("3.0")).find("not major.minor.patch"), std::string::npos);
    EXPECT_NE(load_error("<scene><sensor type=\"perspective\"/></scene>").find("needs a version attribute"), std::string::npos);
    const fs::path dir = temp_dir("test_versions");
    std::ofstream(dir / "old.xml") << "<scene version=\"0.5.0\"/>";
    std::ofstream(dir / "main.xml") << with_version("3.0.0", "<include filename=\"old.xml\"/>");
    try {
        load_scene(dir / "main.xml");
        FAIL() << "an included 0.5 scene must be refused";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("old.xml:1: scene version 0.5.0"), std::string::npos) << e.what();
    }
}

TEST(MitsubaScenes, SpdSpectraNamedIorsAndMetals) {
    const fs::path dir = temp_dir("test_spectra");
    std::ofstream(dir / "ramp.spd") << "# wavelength value\n400 0.2\n500 0.4  # comment\n\n600 0.6\n";
    const LoadedMaterial diffuse = load_material(R"(<bsdf type="diffuse"><spectrum name="reflectance" filename="ramp.spd"/></bsdf>)",
                                                 dir / "scene.xml");
    SampledWavelengths w;
    w.lambda = {450, 380, 700, 550};
    const SampledSpectrum f = diffuse.material->eval({}, {0, 0, 1}, {0, 0, 1}, w, nullptr);
    EXPECT_NEAR(f[0] * kPi, 0.3, 1e-12);
    EXPECT_NEAR(f[1] * kPi, 0.2, 1e-12);  // constant beyond the table
    EXPECT_NEAR(f[2] * kPi, 0.6, 1e-12);
    EXPECT_NEAR(f[3] * kPi, 0.5, 1e-12);
    std::ofstream(dir / "bad.spd") << "400 0.2\n500\n";
    EXPECT_NE(load_error(scene_xml(R"(<shape type="cube"><bsdf type="diffuse"><spectrum name="reflectance" filename="bad.spd"/></bsdf></shape>)"))
                  .find("file not found"), std::string::npos);  // relative to scene.xml in the current directory
    try {
        load_material(R"(<bsdf type="diffuse"><spectrum name="reflectance" filename="bad.spd"/></bsdf>)", dir / "scene.xml");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.spd:2: expected 'wavelength value'"), std::string::npos) << e.what();
    }
    // Named indices: water against air at normal incidence reflects ((n1 - n2) / (n1 + n2))^2.
    const LoadedMaterial water = load_material(R"(<bsdf type="dielectric"><string name="int_ior" value="water"/></bsdf>)");
    const auto s = water.material->sample({}, {0, 0, 1}, w, 0.0, {0.5, 0.5});
    ASSERT_TRUE(s);
    const double r = std::pow((1.333 - 1.000277) / (1.333 + 1.000277), 2);
    EXPECT_NEAR(s->pdf[0], r, 1e-12);
    const std::string unknown = load_error(scene_xml(R"(<shape type="cube"><bsdf type="dielectric"><string name="int_ior" value="glass"/></bsdf></shape>)"));
    EXPECT_NE(unknown.find("'glass' is neither a number nor a known material"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("bk7"), std::string::npos);
    // Metals: Mitsuba's names of the built-in metals load; the others are refused clearly.
    EXPECT_EQ(load_error(scene_xml(R"(<shape type="cube"><bsdf type="conductor"><string name="material" value="Au"/></bsdf></shape>)")), "");
    EXPECT_NE(load_error(scene_xml(R"(<shape type="cube"><bsdf type="conductor"><string name="material" value="Hg"/></bsdf></shape>)"))
                  .find("material 'Hg' is not built in"), std::string::npos);
    EXPECT_NE(load_error(scene_xml(R"(<shape type="cube"><bsdf type="roughconductor"><string name="material" value="Cu_palik"/></bsdf></shape>)"))
                  .find("use 'Cu'"), std::string::npos);
}

TEST(MitsubaScenes, BitmapWrapModesAndFilters) {
    // A 4 x 1 EXR with texel values 0.1, 0.2, 0.3, 0.4 (raw, grey): eval_1 at u outside [0, 1] in each wrap mode.
    const fs::path dir = temp_dir("test_bitmap");
    io::Image ramp(4, 1, 1);
    for (int x = 0; x < 4; ++x) ramp.at(x, 0, 0) = static_cast<float>(0.1 * (x + 1));
    io::write_exr(dir / "ramp.exr", ramp);
    const auto value = [&](const std::string& wrap, const std::string& filter, double u) {
        const LoadedMaterial m = load_material(fmt::format(R"(<bsdf type="blendbsdf"><texture name="weight" type="bitmap">
            <string name="filename" value="ramp.exr"/><string name="wrap_mode" value="{}"/><string name="filter_type" value="{}"/>
            </texture><bsdf type="diffuse"><float name="reflectance" value="0"/></bsdf>
            <bsdf type="diffuse"><float name="reflectance" value="1"/></bsdf></bsdf>)", wrap, filter), dir / "scene.xml");
        ShadingPoint sp;
        sp.uv = {u, 0.5};
        SampledWavelengths w = SampledWavelengths::sample_visible(0.5);
        return m.material->eval(sp, {0, 0, 1}, {0, 0, 1}, w, nullptr)[0] * kPi;  // = the blend weight
    };
    // Texel centres at u = 0.125, 0.375, ...: u = 1.125 is texel 0 repeated, texel 3 mirrored, texel 3 clamped.
    EXPECT_NEAR(value("repeat", "nearest", 1.125), 0.1, 1e-6);
    EXPECT_NEAR(value("mirror", "nearest", 1.125), 0.4, 1e-6);
    EXPECT_NEAR(value("clamp", "nearest", 1.125), 0.4, 1e-6);
    EXPECT_NEAR(value("mirror", "nearest", -0.125), 0.1, 1e-6);
    EXPECT_NEAR(value("repeat", "bilinear", 0.25), 0.15, 1e-6);  // halfway between texels 0 and 1
    EXPECT_NEAR(value("repeat", "bilinear", 0.0), 0.25, 1e-6);   // halfway between texel 3 and (wrapped) texel 0
    EXPECT_NEAR(value("clamp", "bilinear", 0.0), 0.1, 1e-6);
}

TEST(MitsubaScenes, PluginsOutsideTheSubsetAreErrorsWithFileAndLine) {
    const std::pair<std::string, std::string> cases[] = {
        {R"(<integrator type="bdpt"/>)", "unknown integrator plugin 'bdpt'"},
        {R"(<shape type="shapegroup"/>)", "unknown shape plugin 'shapegroup'"},
        {R"(<emitter type="sunsky"/>)", "unknown emitter plugin 'sunsky'"},
        {R"(<shape type="cube"><bsdf type="principled"/></shape>)", "unknown bsdf plugin 'principled'"},
        {R"(<shape type="cube"><bsdf type="diffuse"><texture name="reflectance" type="mesh_attribute"/></bsdf></shape>)",
         "unknown texture plugin 'mesh_attribute'"},
        {R"(<shape type="cube"><bsdf type="roughplastic"><float name="alpha_u" value="0.1"/><float name="alpha_v" value="0.3"/></bsdf></shape>)",
         "anisotropic roughness"},
        {R"(<emitter type="spot"><texture name="texture" type="checkerboard"/></emitter>)", "projected texture is not supported"},
        {R"(<emitter type="envmap"><string name="filename" value="sky.exr"/><boolean name="mis_compensation" value="true"/></emitter>)",
         "mis_compensation is not supported"},
    };
    for (const auto& [body, message] : cases) {
        const std::string xml = scene_xml("\n" + body);
        const std::string error = load_error(xml);
        EXPECT_NE(error.find(message), std::string::npos) << error;
        EXPECT_EQ(error.rfind("scene.xml:", 0), 0u) << error;
    }
    for (const auto& [sensor, message] :
         {std::pair<std::string, std::string>{R"(<sensor type="orthographic"/>)", "unknown sensor plugin 'orthographic'"},
          {R"(<sensor type="perspective"><film type="specfilm"/></sensor>)", "unknown film plugin 'specfilm'"},
          {R"(<sensor type="perspective"><film type="hdrfilm"><rfilter type="bspline"/></film></sensor>)", "unknown rfilter plugin 'bspline'"},
          {R"(<sensor type="perspective"><sampler type="multijitter"/></sensor>)", "unknown sampler plugin 'multijitter'"}}) {
        const std::string error = load_error("<scene version=\"3.0.0\">\n" + sensor + "</scene>");
        EXPECT_NE(error.find(message), std::string::npos) << error;
        EXPECT_EQ(error.rfind("scene.xml:2:", 0), 0u) << error;
    }
}

namespace {

// Files every-plugin scenes refer to: meshes in the three formats, a PNG and an EXR texture, an EXR and an HDR
// environment, a .spd spectrum and an included file.
void write_assets(const fs::path& dir) {
    std::ofstream(dir / "quad.obj") << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n";
    std::ofstream(dir / "tri.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                      "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                      "end_header\n-1 -1 0\n1 -1 0\n0 1 0\n3 0 1 2\n";
    io::Image texture(8, 8, 3);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            texture.at(x, y, 0) = static_cast<float>(x) / 8;
            texture.at(x, y, 1) = static_cast<float>(y) / 8;
            texture.at(x, y, 2) = 0.5f;
        }
    io::write_png(dir / "texture.png", texture);
    io::write_exr(dir / "texture.exr", texture);
    io::Image sky(16, 8, 3, 0.3f);
    for (int x = 0; x < 16; ++x) sky.at(x, 2, 0) = 3.0f;
    io::write_exr(dir / "sky.exr", sky);
    std::ofstream(dir / "eta.spd") << "400 0.3\n700 0.2\n";
    std::ofstream(dir / "k.spd") << "400 3.0\n700 4.0\n";
    std::ofstream(dir / "lights.xml") << R"(<scene version="3.0.0">
        <emitter type="point"><point name="position" x="0" y="-1" z="3"/><float name="intensity" value="$power"/></emitter>
        <emitter type="spot"><transform name="to_world"><lookat origin="2, 0, 3" target="0, 0, 0"/></transform></emitter>
        <emitter type="directional"><vector name="direction" x="0.2" y="0.3" z="-1"/><float name="irradiance" value="0.5"/></emitter>
    </scene>)";
    std::vector<std::uint8_t> file = serialized_mesh(4, {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, {}, {}, {{0, 1, 2}}, false);
    put(file, std::uint64_t{0});
    put(file, std::uint32_t{1});
    std::ofstream(dir / "mesh.serialized", std::ios::binary).write(reinterpret_cast<const char*>(file.data()),
                                                                   static_cast<long>(file.size()));
    // A flat (uncompressed) Radiance file: every texel (128, 128, 128) with exponent 127, i.e. 0.25.
    std::string texels;
    for (int i = 0; i < 12; ++i) texels += "\x80\x80\x80\x7F";
    std::ofstream(dir / "sky.hdr", std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 3 +X 4\n" << texels;
}

// Every BSDF on its own small shape in a row, every shape kind, every emitter: rendered tiny, finite, not black.
std::string every_plugin_scene(const std::string& integrator, const std::string& sensor_type,
                               const std::string& sensor, const std::string& rfilter, const std::string& sky) {
    const char* bsdfs[] = {
        R"(<bsdf type="diffuse"><texture name="reflectance" type="bitmap"><string name="filename" value="texture.png"/>
            <string name="wrap_mode" value="mirror"/></texture></bsdf>)",
        R"(<bsdf type="conductor"><spectrum name="eta" filename="eta.spd"/><spectrum name="k" filename="k.spd"/></bsdf>)",
        R"(<bsdf type="roughconductor"><string name="material" value="Al"/><string name="distribution" value="ggx"/></bsdf>)",
        R"(<bsdf type="dielectric"><string name="int_ior" value="water"/></bsdf>)",
        R"(<bsdf type="thindielectric"/>)",
        R"(<bsdf type="roughdielectric"><float name="alpha" value="0.2"/></bsdf>)",
        R"(<bsdf type="plastic"><rgb name="diffuse_reflectance" value="0.2, 0.4, 0.8"/></bsdf>)",
        R"(<bsdf type="roughplastic"><texture name="diffuse_reflectance" type="checkerboard"/></bsdf>)",
        R"(<bsdf type="twosided"><ref id="shared"/></bsdf>)",
        R"(<bsdf type="blendbsdf"><texture name="weight" type="bitmap"><string name="filename" value="texture.exr"/></texture>
            <bsdf type="diffuse"/><bsdf type="conductor"/></bsdf>)",
        R"(<bsdf type="mask"><float name="opacity" value="0.5"/><bsdf type="diffuse"/></bsdf>)",
        R"(<bsdf type="bumpmap"><texture type="bitmap"><boolean name="raw" value="true"/><string name="filename" value="texture.png"/></texture>
            <bsdf type="roughplastic"/></bsdf>)",
        R"(<bsdf type="normalmap"><texture name="normalmap" type="bitmap"><boolean name="raw" value="true"/>
            <string name="filename" value="texture.png"/></texture><bsdf type="diffuse"/></bsdf>)",
        R"(<bsdf type="ggx_stats"><string name="material" value="Au"/><float name="sigma" value="0.05"/><float name="corr_length" value="2"/>
            <float name="gamma" value="4"/></bsdf>)",
    };
    std::string shapes;
    const char* kinds[] = {"rectangle", "disk", "cube", "sphere", "cylinder", "obj", "ply", "serialized"};
    int i = 0;
    for (const char* bsdf : bsdfs) {
        const std::string kind = kinds[i % 8];
        std::string extra;
        if (kind == "obj") extra = R"(<string name="filename" value="quad.obj"/>)";
        if (kind == "ply") extra = R"(<string name="filename" value="tri.ply"/><boolean name="face_normals" value="true"/>)";
        if (kind == "serialized") extra = R"(<string name="filename" value="mesh.serialized"/>)";
        shapes += fmt::format(R"(<shape type="{}">{}<transform name="to_world"><scale value="0.3"/><translate x="{}" y="{}" z="0.3"/></transform>{}</shape>)",
                              kind, extra, -1.5 + 0.75 * (i % 5), -0.8 + 0.8 * (i / 5), bsdf) + "\n";
        ++i;
    }
    return fmt::format(R"(<scene version="3.0.0">
        <default name="power" value="4"/>
        {}
        <sensor type="{}"><float name="fov" value="50"/>{}
            <transform name="to_world"><lookat origin="0, -4, 3" target="0, 0, 0" up="0, 0, 1"/></transform>
            <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="16"/>
                <string name="pixel_format" value="rgba"/>{}</film>
            <sampler type="independent"><integer name="sample_count" value="4"/></sampler></sensor>
        <bsdf type="roughconductor" id="shared"><float name="alpha" value="0.3"/></bsdf>
        <shape type="rectangle"><transform name="to_world"><scale value="4"/></transform><bsdf type="diffuse"/></shape>
        <shape type="disk"><transform name="to_world"><scale value="0.3"/><rotate x="1" angle="180"/><translate z="2.5"/></transform>
            <emitter type="area"><rgb name="radiance" value="5, 5, 4"/></emitter></shape>
        {}
        <include filename="lights.xml"/>
        {}
    </scene>)", integrator, sensor_type, sensor, rfilter, shapes, sky);
}

}  // namespace

TEST(MitsubaScenes, EveryPluginTogether) {
    const fs::path dir = temp_dir("test_every_plugin");
    write_assets(dir);
    const std::string variants[][5] = {
        {R"(<integrator type="path"><integer name="max_depth" value="6"/></integrator>)", "perspective", "",
         R"(<rfilter type="tent"/>)",
         R"(<emitter type="envmap"><string name="filename" value="sky.exr"/><float name="scale" value="0.5"/></emitter>)"},
        {R"(<integrator type="direct"><boolean name="hide_emitters" value="true"/></integrator>)", "thinlens",
         R"(<float name="aperture_radius" value="0.05"/><float name="focus_distance" value="5"/>)",
         R"(<rfilter type="lanczos"/>)", R"(<emitter type="envmap"><string name="filename" value="sky.hdr"/></emitter>)"},
        {R"(<integrator type="path"/>)", "perspective", "", R"(<rfilter type="mitchell"/>)",
         R"(<emitter type="constant"><rgb name="radiance" value="0.1, 0.2, 0.3"/></emitter>)"},
    };
    for (const auto& v : variants) {
        const std::string xml = every_plugin_scene(v[0], v[1], v[2], v[3], v[4]);
        std::ofstream(dir / "scene.xml") << xml;
        auto scene = load_scene(dir / "scene.xml", {{"power", "6"}});
        RenderOptions options;
        options.progress = false;
        const Film film = surfscatter::render::render(*scene, options);
        double sum = 0;
        for (int y = 0; y < film.height(); ++y)
            for (int x = 0; x < film.width(); ++x) {
                const Vec3 xyz = film.xyz(x, y);
                ASSERT_TRUE(std::isfinite(xyz.x) && std::isfinite(xyz.y) && std::isfinite(xyz.z)) << v[0];
                sum += xyz.y;
            }
        EXPECT_GT(sum, 0.0) << v[0];
        write_film(film, scene->film, dir / "every_plugin.exr");
    }
}
