#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "render_test_util.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/surface/synthesis.hpp"

using namespace surfscatter;
using namespace surfscatter::render;
using namespace surfscatter::render::test;
namespace fs = std::filesystem;


TEST(XmlLoader, LoadsSensorFilmSamplerIntegrator) {
    const std::string xml = R"(<scene version="3.0.0">
  <default name="spp" value="9"/>
  <integrator type="path"><integer name="max_depth" value="4"/><integer name="rr_depth" value="3"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="30"/><string name="fov_axis" value="y"/>
    <float name="near_clip" value="0.1"/><float name="far_clip" value="50"/>
    <float name="principal_point_offset_x" value="0.01"/>
    <transform name="to_world"><lookat origin="1, 2, 3" target="0, 0, 0" up="0, 0, 1"/></transform>
    <film type="hdrfilm"><integer name="width" value="40"/><integer name="height" value="30"/>
      <rfilter type="gaussian"/></film>
    <sampler type="independent"><integer name="sample_count" value="$spp"/><integer name="seed" value="5"/></sampler>
  </sensor>
</scene>)";
    auto scene = load_scene_from_string(xml, "scene.xml");
    EXPECT_EQ(scene->integrator.max_depth, 4);
    EXPECT_EQ(scene->integrator.rr_depth, 3);
    EXPECT_DOUBLE_EQ(scene->camera.fov_degrees, 30);
    EXPECT_EQ(scene->camera.fov_axis, "y");
    EXPECT_DOUBLE_EQ(scene->camera.near_clip, 0.1);
    EXPECT_DOUBLE_EQ(scene->camera.principal_point_offset_x, 0.01);
    EXPECT_EQ(scene->film.width, 40);
    EXPECT_EQ(scene->film.filter->name(), "gaussian");
    EXPECT_EQ(scene->sampler.sample_count, 9);
    EXPECT_EQ(scene->sampler.seed, 5u);
    const Vec3 origin = scene->camera.to_world.point({0, 0, 0});
    EXPECT_NEAR(origin.y, 2, 1e-12);
    // -D overrides <default>.
    auto overridden = load_scene_from_string(xml, "scene.xml", {{"spp", "3"}});
    EXPECT_EQ(overridden->sampler.sample_count, 3);
}

TEST(XmlLoader, TransformsComposeInMitsubaOrder) {
    const std::string body = R"(<shape type="rectangle">
        <transform name="to_world"><scale x="2" y="1" z="1"/><rotate z="1" angle="90"/><translate x="5"/></transform>
        </shape>)";
    auto scene = load_scene_from_string(scene_xml(body), "scene.xml");
    // Point (1, 0, 0) -> scale (2, 0, 0) -> rotate (0, 2, 0) -> translate (5, 2, 0): a ray down at (5, 1.9) hits.
    Ray ray{{5, 1.9, 1}, {0, 0, -1}, 0, 10};
    EXPECT_TRUE(scene->intersect(ray).has_value());
    ray.origin = {5, 2.1, 1};
    EXPECT_FALSE(scene->intersect(ray).has_value());
}

TEST(XmlLoader, IncludeAndReferences) {
    const fs::path dir = temp_dir("test_xml");
    std::ofstream(dir / "materials.xml") << R"(<scene version="3.0.0">
  <bsdf type="diffuse" id="grey"><float name="reflectance" value="0.3"/></bsdf>
  <texture type="checkerboard" id="checks"/>
</scene>)";
    const std::string body = R"(<include filename="materials.xml"/>
        <shape type="cube"><ref id="grey"/></shape>
        <shape type="disk"><bsdf type="diffuse"><ref name="reflectance" id="checks"/></bsdf></shape>)";
    std::ofstream(dir / "main.xml") << scene_xml(body);
    EXPECT_NO_THROW(load_scene(dir / "main.xml"));
}

// A GHS from a height map's own PSD: <string name="psd" value="measured"/> with surface_file; the extrapolation of
// the measured PSD reaches the user as a scene note with the bsdf's file and line.
TEST(XmlLoader, MeasuredPsdFromASurfaceFile) {
    const fs::path dir = temp_dir("test_xml");
    heightmap::write_gsf(surface::synthesize_surface(surface::KCorrelation(0.05, 1.0, 3.0), {256, 256, 0.1}, 5),
                       dir / "map.gsf");
    const std::string body = R"(<shape type="rectangle"><bsdf type="ghs"><string name="psd" value="measured"/>
            <string name="surface_file" value="map.gsf"/></bsdf></shape>)";
    std::ofstream(dir / "measured.xml") << scene_xml(body);
    const auto scene = load_scene(dir / "measured.xml");
    const auto note = std::find_if(scene->notes.begin(), scene->notes.end(),
                                   [](const std::string& n) { return n.find("measured PSD of") != std::string::npos; });
    ASSERT_NE(note, scene->notes.end());
    EXPECT_EQ(note->rfind((dir / "measured.xml").string() + ":", 0), 0u) << *note;
}

// A profile as a scene's surface_file (issue 33: the real profiles gave BRDFs but no render). Written here as an .hfm
// export of a synthesised KC profile (sigma_h 0.1 um, L_c 5 um, gamma 3, 4096 points 0.5 um apart): each model plugin
// (ghs_ssa and ggx_stats here) takes the profile's own spectrum as an isotropic surface's (psd measured), noting the
// profile's preparation and the route; its BSDF is finite and positive off specular. An areal preparation option or psd file is an error naming
// the file.
TEST(XmlLoader, ProfileAsSurfaceFile) {
    const fs::path dir = temp_dir("test_xml_profile");
    const std::vector<double> h = surface::synthesize_profile(surface::KCorrelation(0.1, 5.0, 3.0), 4096, 0.5, 7);
    const std::string hfm = (dir / "profile.hfm").string();
    {
        std::ofstream out(hfm);
        out << "X;Y;valid\n[mm];[mm];[1/0]\n";
        for (std::size_t i = 0; i < h.size(); ++i)
            out << fmt::format("{:.7f};{:.10f};1\n", 0.0005 * static_cast<double>(i), h[i] * 1e-3);
    }
    const auto bsdf = [&](const std::string& model, const std::string& extra) {
        return "<bsdf type=\"" + model + "\"><string name=\"material\" value=\"Al\"/><string name=\"surface_file\" value=\"" +
               hfm + "\"/>" + extra + "</bsdf>";
    };
    const SampledWavelengths lambda = SampledWavelengths::sample_visible(0.37);
    const Vec3 wi = spherical_direction(30 * kDegree, 0), wo = spherical_direction(45 * kDegree, kPi);
    // Two models: the route (load_height_map) is the same for all four, and ghs's and two_scale's tables cost
    // minutes here.
    for (const std::string model : {"ghs_ssa", "ggx_stats"}) {
        const LoadedMaterial m = load_material(bsdf(model, "<string name=\"psd\" value=\"measured\"/>"));
        const auto& notes = m.scene->notes;
        const auto has = [&](const std::string& text) {
            return std::any_of(notes.begin(), notes.end(), [&](const std::string& n) { return n.find(text) != std::string::npos; });
        };
        EXPECT_TRUE(has("profile.hfm: profile: form plane (a least-squares line), 4096 points 0.5 um apart")) << model;
        EXPECT_TRUE(has("inverse Abel transform of the profile's Hann-windowed 1-D PSD")) << model;
        const SampledSpectrum f = m.material->eval({}, wi, wo, lambda, nullptr);
        for (int k = 0; k < spectrum::kSpectrumSamples; ++k)
            EXPECT_TRUE(std::isfinite(f[k]) && f[k] > 0) << model << " " << f[k];
    }
    const std::string areal = load_error(scene_xml("<shape type=\"rectangle\">" +
                                                   bsdf("ghs", "<string name=\"outliers\" value=\"fill\"/>") + "</shape>"));
    EXPECT_NE(areal.find(hfm + ": outliers, row_alignment, lambda_s and lambda_c apply to areal maps; a profile is "
                               "prepared by its form only"),
              std::string::npos)
        << areal;
    const std::string file =
        load_error(scene_xml("<shape type=\"rectangle\">" + bsdf("ghs", "<string name=\"psd\" value=\"file\"/>") + "</shape>"));
    EXPECT_NE(file.find("psd file: " + hfm + " is a profile: its own spectrum is the surface (psd measured)"),
              std::string::npos)
        << file;
}

// psd_fit elliptical: the elliptical KC fitted to surface_file, its fit a scene note; with psd kc an error at its line.
TEST(XmlLoader, PsdFitEllipticalFromASurfaceFile) {
    const std::string opd = (fs::path(SURFSCATTER_SHARED_DATA) / "realdata" / "heightmaps" / "opd-1.opd").string();
    const auto scene = load_scene_from_string(
        scene_xml("<shape type=\"rectangle\"><bsdf type=\"ghs_ssa\"><string name=\"surface_file\" value=\"" + opd +
                  "\"/><string name=\"psd_fit\" value=\"elliptical\"/></bsdf></shape>"),
        "scene.xml");
    const auto note = std::find_if(scene->notes.begin(), scene->notes.end(), [](const std::string& n) {
        return n.find("psd_fit elliptical of") != std::string::npos;
    });
    ASSERT_NE(note, scene->notes.end());
    EXPECT_NE(note->find("the anisotropy is significant"), std::string::npos) << *note;
    const std::string kc = scene_xml(
        "<shape type=\"rectangle\">\n<bsdf type=\"ghs\"><float name=\"sigma\" value=\"0.05\"/><float name=\"corr_length\" "
        "value=\"2\"/><float name=\"gamma\" value=\"3\"/>\n<string name=\"psd_fit\" value=\"elliptical\"/></bsdf></shape>");
    EXPECT_NE(load_error(kc).find(fmt::format("scene.xml:{}: parameter 'psd_fit' does not apply to bsdf 'ghs': used with "
                                              "psd file (the KC fitted to a height map) only",
                                              line_of(kc, "psd_fit"))),
              std::string::npos)
        << load_error(kc);
}

TEST(XmlLoader, ErrorsCarryFileAndLine) {
    // Syntax error on line 3.
    // A <float> left open: pugixml reports the mismatched end tag on line 4.
    EXPECT_EQ(load_error("<scene version=\"3.0.0\">\n<sensor type=\"perspective\">\n<float name=\"fov\" value=\"3\">\n</scene>")
                  .rfind("scene.xml:4: XML syntax error", 0), 0u);
    EXPECT_NE(load_error("<scene>\n\n<sensor type=\"perspective\"\n</scene>").find("XML syntax error"), std::string::npos);

    const std::string teapot = scene_xml("<shape type=\"teapot\"/>");
    const std::string message = load_error(teapot);
    EXPECT_NE(message.find(fmt::format("scene.xml:{}: unknown shape plugin 'teapot'", line_of(teapot, "teapot"))),
              std::string::npos) << message;

    const std::string roughness = scene_xml(
        "<shape type=\"rectangle\">\n<bsdf type=\"diffuse\"><float name=\"roughness\" value=\"1\"/></bsdf></shape>");
    const std::string unknown_param = load_error(roughness);
    EXPECT_NE(unknown_param.find(fmt::format("scene.xml:{}: unknown parameter 'roughness' of bsdf 'diffuse'",
                                             line_of(roughness, "roughness"))), std::string::npos)
        << unknown_param;

    const std::string nowhere = scene_xml("<shape type=\"obj\"><string name=\"filename\" value=\"nowhere.obj\"/></shape>");
    const std::string missing = load_error(nowhere);
    EXPECT_NE(missing.find(fmt::format("scene.xml:{}: file not found", line_of(nowhere, "nowhere"))), std::string::npos)
        << missing;

    const std::string undefined = load_error(scene_xml("<shape type=\"sphere\"><float name=\"radius\" value=\"$r\"/></shape>"));
    EXPECT_NE(undefined.find("parameter $r is not defined"), std::string::npos) << undefined;

    const std::string one_x = scene_xml("<shape type=\"sphere\"><float name=\"radius\" value=\"1x\"/></shape>");
    const std::string bad_number = load_error(one_x);
    EXPECT_NE(bad_number.find(fmt::format("scene.xml:{}: radius: '1x' is not a finite number", line_of(one_x, "1x"))),
              std::string::npos) << bad_number;

    EXPECT_NE(load_error(scene_xml("<shape type=\"cube\"><ref id=\"nothing\"/></shape>")).find("undefined id 'nothing'"),
              std::string::npos);
    EXPECT_NE(load_error("<scene version=\"3.0.0\"/>").find("no <sensor>"), std::string::npos);
    EXPECT_NE(load_error(scene_xml("<emitter type=\"projector\"/>")).find("unknown emitter plugin 'projector'"),
              std::string::npos);
    EXPECT_NE(load_error(scene_xml("<bogus/>")).find("unknown element <bogus>"), std::string::npos);
}

TEST(MeshFiles, ObjAndPlyLoad) {
    const fs::path dir = temp_dir("test_xml");
    std::ofstream(dir / "quad.obj") << "# quad\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                       "f 1/1 2/2 3/3 4/4\n";
    const TriangleMesh obj = load_obj(dir / "quad.obj");
    EXPECT_EQ(obj.triangles.size(), 2u);
    EXPECT_EQ(obj.uvs.size(), 4u);  // corners with the same v/vt share a vertex
    EXPECT_EQ(obj.uvs[0].y, 1.0);   // Mitsuba's flip_tex_coords: v -> 1 - v
    EXPECT_EQ(load_obj(dir / "quad.obj", false).uvs[0].y, 0.0);
    std::ofstream(dir / "tri.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                      "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                      "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const TriangleMesh ply = load_ply(dir / "tri.ply");
    EXPECT_EQ(ply.triangles.size(), 1u);
    EXPECT_EQ(ply.positions[1], Vec3(1, 0, 0));
    // Binary little-endian with normals.
    {
        std::ofstream out(dir / "tri_bin.ply", std::ios::binary);
        out << "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
               "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nelement face 1\n"
               "property list uchar uint vertex_indices\nend_header\n";
        const float v[18] = {0, 0, 0, 0, 0, 1, 2, 0, 0, 0, 0, 1, 0, 2, 0, 0, 0, 1};
        out.write(reinterpret_cast<const char*>(v), sizeof v);
        const unsigned char n = 3;
        const unsigned idx[3] = {0, 1, 2};
        out.write(reinterpret_cast<const char*>(&n), 1);
        out.write(reinterpret_cast<const char*>(idx), sizeof idx);
    }
    const TriangleMesh bin = load_ply(dir / "tri_bin.ply");
    EXPECT_EQ(bin.positions[2], Vec3(0, 2, 0));
    EXPECT_EQ(bin.normals.size(), 3u);
    std::ofstream(dir / "bad.obj") << "v 0 0 0\nf 1 2 3\n";
    EXPECT_THROW(load_obj(dir / "bad.obj"), Error);
    std::ofstream(dir / "bad.ply") << "ply\nformat binary_big_endian 1.0\n";
    EXPECT_THROW(load_ply(dir / "bad.ply"), Error);
}

TEST(Camera, ProjectInvertsGenerateRay) {
    CameraSettings settings;
    settings.to_world = Transform::look_at({0.3, -1, 0.8}, {0, 0, 0}, {0, 0, 1});
    settings.fov_degrees = 50;
    settings.principal_point_offset_x = 0.02;
    settings.principal_point_offset_y = -0.03;
    const Camera camera(settings, 64, 48);
    for (const Vec2 pixel : {Vec2(0.5, 0.5), Vec2(10.25, 40.75), Vec2(63.5, 1.5)}) {
        const Ray ray = camera.generate_ray(pixel.x, pixel.y);
        const auto back = camera.project(ray.origin + ray.direction * 2.0);
        ASSERT_TRUE(back.has_value());
        EXPECT_NEAR(back->x, pixel.x, 1e-9);
        EXPECT_NEAR(back->y, pixel.y, 1e-9);
    }
    EXPECT_FALSE(camera.project({0.6, -2, 1.6}).has_value());  // behind the camera
}

TEST(XmlLoader, SurfaceFileOfAnyFormatIsReadOnceAndReported) {
    // The real Wyko file (116 invalid points) behind two BSDFs, with a form: one read, one note.
    const std::string opd = (fs::path(SURFSCATTER_SHARED_DATA) / "realdata" / "heightmaps" / "opd-1.opd").string();
    const std::string bsdf = "<bsdf type=\"ggx_stats\"><string name=\"surface_file\" value=\"" + opd +
                             "\"/><string name=\"form\" value=\"poly2\"/></bsdf>";
    auto scene = load_scene_from_string(
        scene_xml("<shape type=\"rectangle\">" + bsdf + "</shape>\n<shape type=\"sphere\">" + bsdf + "</shape>"),
        "scene.xml");
    ASSERT_EQ(scene->notes.size(), 1u);
    EXPECT_NE(scene->notes[0].find("opd-1.opd: Wyko OPD files (.opd), 640 x 480 points"), std::string::npos)
        << scene->notes[0];
    EXPECT_NE(scene->notes[0].find("99.96 % valid"), std::string::npos) << scene->notes[0];

    const std::string bad_form = scene_xml("<shape type=\"rectangle\"><bsdf type=\"ggx_stats\"><string name=\"surface_file\" "
                                           "value=\"" + opd + "\"/><string name=\"form\" value=\"sphere\"/></bsdf></shape>");
    EXPECT_NE(load_error(bad_form).find(fmt::format("scene.xml:{}: bsdf 'ggx_stats': form must be none, plane, poly2",
                                                    line_of(bad_form, "ggx_stats"))),
              std::string::npos)
        << load_error(bad_form);
    const fs::path garbage = temp_dir("test_xml_heightmap") / "garbage.dat";
    {
        std::ofstream out(garbage, std::ios::binary);
        for (int i = 0; i < 4000; ++i) out.put(static_cast<char>((i * 37) % 256));
    }
    const std::string unknown = scene_xml("<shape type=\"rectangle\"><bsdf type=\"ggx_stats\"><string name=\"surface_file\" "
                                          "value=\"" + garbage.string() + "\"/></bsdf></shape>");
    EXPECT_NE(load_error(unknown).find("garbage.dat: unknown height map format"), std::string::npos)
        << load_error(unknown);
}
