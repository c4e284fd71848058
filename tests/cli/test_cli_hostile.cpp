// Hostile inputs through the binary (issue 16): every case either exits 2 with one printable line that names the
// bad value and where it came from (file:line for scenes), or, for a huge but valid value, exits 0 with finite
// output. Never a crash, a hang, "internal error", NaN or Inf, or an option silently ignored. One table row per
// case; the files they need are written once by the suite's fixture.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "cli_runner.hpp"
#include "heightmap/zip_archive.hpp"
#include "surfscatter/io/image.hpp"
#include "surfscatter/photo/camera_model.hpp"
#include "surfscatter/heightmap/height_map.hpp"
#include "surfscatter/heightmap/io.hpp"

namespace fs = std::filesystem;
using surfscatter::test::CliResult;
using surfscatter::test::run_cli;

namespace {

fs::path dir() { return surfscatter::test::scratch_directory("surfscatter_test_cli_hostile"); }

// "@D@" in a case's arguments and message stands for the scratch directory, "@S@" for the source tree (the fuzz
// corpus's regression inputs).
std::string expand(std::string text) {
    for (std::size_t at; (at = text.find("@D@")) != std::string::npos;) text.replace(at, 3, dir().string());
    for (std::size_t at; (at = text.find("@S@")) != std::string::npos;) text.replace(at, 3, SURFSCATTER_SOURCE_DIR);
    return text;
}

// A small renderable scene: a plane under a point light. `film`, `shape` and `scene` are inserted into the film,
// the plane and the scene; $size and $exposure are parameters with defaults.
std::string scene(const std::string& film = "", const std::string& shape = "", const std::string& extra = "") {
    return "<scene version=\"3.0.0\">\n"
           "  <default name=\"size\" value=\"8\"/>\n"
           "  <default name=\"exposure\" value=\"0\"/>\n"
           "  <sensor type=\"perspective\">\n"
           "    <transform name=\"to_world\"><lookat origin=\"0, -2, 2\" target=\"0, 0, 0\" up=\"0, 0, 1\"/></transform>\n"
           "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"$size\"/><integer name=\"height\" value=\"$size\"/>\n"
           "      <float name=\"exposure\" value=\"$exposure\"/>" + film + "</film>\n"
           "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"2\"/></sampler>\n"
           "  </sensor>\n"
           "  <shape type=\"rectangle\">" + shape + "</shape>\n"
           "  <emitter type=\"point\"><point name=\"position\" x=\"0\" y=\"0\" z=\"1\"/>\n"
           "    <rgb name=\"intensity\" value=\"1\"/></emitter>\n" + extra +
           "</scene>\n";
}

std::string nested(const std::string& open, const std::string& close, const std::string& inner, int depth) {
    std::string text;
    for (int i = 0; i < depth; ++i) text += open;
    text += inner;
    for (int i = 0; i < depth; ++i) text += close;
    return text;
}

// Written under a private name and renamed: ctest runs the cases as parallel processes that each write the same
// files, and a reader must never see one half written.
void write(const std::string& name, const std::string& bytes) {
    const fs::path partial = dir() / (name + ".partial." + std::to_string(getpid()));
    std::ofstream(partial, std::ios::binary) << bytes;
    fs::rename(partial, dir() / name);
}

// Issue 26, rules 4 and 7 (docs/RELIABILITY.md "Rules on conflicts, unchecked objects, domains and messages"): the
// files of their rows (kRuleCases below).
void write_rule_files() {
    // Conflicts name both places.
    std::string two_integrators = scene("", "", "  <integrator type=\"path\"/>\n  <integrator type=\"direct\"/>\n");
    write("integrator_twice.xml", two_integrators);
    std::string defaults = scene();
    defaults.replace(defaults.find("  <sensor"), 0, "  <default name=\"size\" value=\"16\"/>\n");
    write("default_conflict.xml", defaults);
    std::string same_default = scene();
    same_default.replace(same_default.find("  <sensor"), 0, "  <default name=\"size\" value=\"8\"/>\n");
    write("default_repeated.xml", same_default);
    std::string samplers = scene();
    samplers.replace(samplers.find("  </sensor>"), 0, "    <sampler type=\"independent\"/>\n");
    write("sampler_twice.xml", samplers);
    write("shape_two_bsdfs.xml", scene("", "<bsdf type=\"diffuse\"/>\n    <bsdf type=\"conductor\"/>"));
    std::string gsf = "Gwyddion Simple Field 1.0\nXRes = 2\nYRes = 2\nXRes = 3\nXYUnits = m\nZUnits = m\n";
    gsf.append(4 - gsf.size() % 4, '\0');
    gsf.append(16, '\0');
    write("xres_twice.gsf", gsf);
    write("study_key_twice.json", "{\"models\": [{\"name\": \"a\", \"model\": \"ggx\", \"alpha\": 0.1}],\n"
                                  " \"wavelengths\": [500],\n \"albedo\": {\"theta_i\": [0]},\n"
                                  " \"wavelengths\": [600]}\n");
    write("study_model_key_twice.json", "{\"models\": [{\"name\": \"a\", \"model\": \"ggx\",\n  \"model\": \"ghs\"}],\n"
                                        " \"wavelengths\": [500], \"albedo\": {\"theta_i\": [0]}}\n");
    fs::create_directories(dir() / "manifest_twice");
    write("manifest_twice/study.json", "{\"models\": [{\"name\": \"a\", \"model\": \"ggx\", \"alpha\": 0.1}],\n"
                                       " \"wavelengths\": [500], \"albedo\": {\"theta_i\": [0]}}\n");
    write("manifest_twice/manifest.json", "{\"format\": \"surfscatter study manifest 1\",\n \"jobs\": [],\n \"jobs\": []}\n");
    write("data_twice.yml", "DATA:\n  - type: tabulated nk\n    data: |\n        0.4 1 2\n        0.7 1 2\n"
                            "DATA:\n  - type: formula 1\n    wavelength_range: 0.3 1.0\n    coefficients: 0 1 0.1\n");
    // Every parsed object is checked, referenced or not.
    write("unreferenced_foobar.xml", scene("", "", "  <bsdf type=\"foobar\" id=\"unused\"/>\n"));
    write("unreferenced_bad_parameter.xml",
          scene("", "", "  <texture type=\"checkerboard\" id=\"unused\"><float name=\"colour0\" value=\"1\"/></texture>\n"));
    // Values out of the physical domain.
    write("spectrum_wavelength_negative.xml",
          scene("", "<emitter type=\"area\"><spectrum name=\"radiance\" value=\"-5:1, 500:1\"/></emitter>"));
    write("zero_wavelength.spd", "0 1\n500 1\n");
    write("spd_wavelength_zero.xml",
          scene("", "<emitter type=\"area\"><spectrum name=\"radiance\" filename=\"zero_wavelength.spd\"/></emitter>"));
    write("negative_n.yml", "DATA:\n  - type: tabulated nk\n    data: |\n        0.4 1 2\n        0.7 -1 2\n");
    write("negative_k_only.yml", "DATA:\n  - type: tabulated n\n    data: |\n        0.4 1\n        0.7 1\n"
                                 "  - type: tabulated k\n    data: |\n        0.4 2\n        0.7 -2\n");
    write("negative_n.csv", "wavelength_nm,n,k\n400,1,2\n700,-0.5,2\n");
    write("subnormal_wavelength.yml", "DATA:\n  - type: tabulated nk\n    data: |\n        1e-320 1 2\n        0.7 1 2\n");
    write("study_number_1e400.json", "{\"models\": [{\"name\": \"a\", \"model\": \"ggx\", \"alpha\": 0.1}],\n"
                                     " \"wavelengths\": [1e400], \"albedo\": {\"theta_i\": [0]}}\n");
    // Messages: a --surface map the model refuses (white noise has no KC fit).
    std::vector<double> noise(64 * 64);
    std::uint64_t state = 777;
    for (double& h : noise) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        h = static_cast<double>(state >> 11) * 0x1.0p-53 - 0.5;
    }
    const fs::path noise_partial = dir() / ("noise.partial." + std::to_string(getpid()) + ".gsf");
    surfscatter::heightmap::write_gsf(surfscatter::heightmap::HeightMap(64, 64, 0.1, 0.1, noise), noise_partial);
    fs::rename(noise_partial, dir() / "white_noise.gsf");
}

struct HostileCase {
    std::string name;               // test name
    std::vector<std::string> args;  // "@D@" = scratch directory
    int exit_code;                  // 2: bad input; 0: a huge but valid value with finite output
    std::string message;            // substring of stderr (exit 2)
    // Issue 26, checked writes: a shell prefix run before the command ("ulimit -f 16;": a full disk after 8 KiB), a
    // file taking stdout instead of the capture ("/dev/full"), and a file the failed command must not leave behind
    // (nor a temporary file beside it).
    std::string shell_prefix = "";
    std::string stdout_path = "";
    std::string absent = "";
};

void PrintTo(const HostileCase& c, std::ostream* os) { *os << c.name; }

class Hostile : public testing::TestWithParam<HostileCase> {
public:
    static void SetUpTestSuite() {
        write("ok.xml", scene());
        write("twosided_30000.xml", scene("", nested("<bsdf type=\"twosided\">", "</bsdf>", "<bsdf type=\"diffuse\"/>", 30000)));
        write("checker_30000.xml",
              scene("", "<bsdf type=\"diffuse\">" +
                            nested("<texture type=\"checkerboard\" name=\"color0\">", "</texture>", "", 30000) + "</bsdf>"));
        write("lookat_empty.xml", "<scene version=\"3.0.0\"><sensor type=\"perspective\"><transform name=\"to_world\">\n"
                                  "<lookat origin=\"0,, -1.6, 0.9\" target=\"0, 0, 0\" up=\"0, 0, 1\"/></transform></sensor>"
                                  "</scene>\n");
        write("rgb_empty.xml", scene("", "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.2,,0.5\"/></bsdf>"));
        write("rgb_huge.xml", scene("", "<emitter type=\"area\"><rgb name=\"radiance\" value=\"1e300\"/></emitter>"));
        write("float_text.xml", scene("", "", "  <shape type=\"sphere\"><float name=\"radius\" value=\"1\">hello</float></shape>\n"));
        write("translate_child.xml",
              scene("", "<transform name=\"to_world\"><translate x=\"1\"><scale value=\"2\"/></translate></transform>"));
        write("shape_text.xml", scene("", "stray words"));
        write("two_roots.xml", scene() + "<scene version=\"3.0.0\"/>\n");
        std::string literal_exposure = scene();
        literal_exposure.replace(literal_exposure.find("$exposure"), 9, "2000");
        write("film_exposure.xml", literal_exposure);
        write("film_white_balance.xml", scene("<string name=\"white_balance\" value=\"foo\"/>"));
        write("blackbody_negative.xml",
              scene("", "", "  <emitter type=\"point\"><point name=\"position\" x=\"0\" y=\"0\" z=\"2\"/>\n"
                            "    <spectrum name=\"intensity\" type=\"blackbody\"><float name=\"temperature\" value=\"2700\"/>"
                            "<float name=\"scale\" value=\"-1\"/></spectrum></emitter>\n"));
        write("spectrum_negative.xml", scene("", "<emitter type=\"area\"><spectrum name=\"radiance\" value=\"-1\"/></emitter>"));
        write("ghs.xml", scene("", "<bsdf type=\"ghs\"><string name=\"material\" value=\"Al\"/>"
                                   "<float name=\"sigma\" value=\"0.1\"/><float name=\"corr_length\" value=\"$corr_length\"/>"
                                   "<float name=\"gamma\" value=\"3\"/></bsdf>", "  <default name=\"corr_length\" value=\"2\"/>\n"));
        write("ggx_stats_smoothing.xml",
              scene("", "<bsdf type=\"ggx_stats\"><string name=\"alpha_from\" value=\"measured\"/>"
                        "<float name=\"smoothing\" value=\"1\"/><float name=\"sigma\" value=\"0.1\"/>"
                        "<float name=\"corr_length\" value=\"2\"/><float name=\"gamma\" value=\"4\"/></bsdf>"));
        write("ghs_ssa_renormalization.xml",
              scene("", "<bsdf type=\"ghs_ssa\"><boolean name=\"renormalization\" value=\"false\"/>"
                        "<float name=\"sigma\" value=\"0.1\"/><float name=\"corr_length\" value=\"2\"/>"
                        "<float name=\"gamma\" value=\"3\"/></bsdf>"));
        write("include_zero.xml", "<scene version=\"3.0.0\">\n  <include filename=\"/dev/zero\"/>\n</scene>\n");
        write("include_self.xml", "<scene version=\"3.0.0\">\n  <include filename=\"include_self.xml\"/>\n</scene>\n");
        write("integer_huge.xml", scene("<integer name=\"crop_width\" value=\"1e10\"/>"));
        write("matrix_huge.xml",
              scene("", "<transform name=\"to_world\"><scale value=\"1e200\"/><scale value=\"1e200\"/></transform>"));
        write("sphere_huge.xml", scene("", "", "  <shape type=\"sphere\"><float name=\"radius\" value=\"1e300\"/></shape>\n"));
        write("text_outside.xml", "<scene version=\"3.0.0\"/>\ntrailing words\n");

        // Meshes.
        const std::string ply_head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                     "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n"
                                     "0 0 0\n1 0 0\n0 1 0\n";
        write("face_4e9.ply", ply_head + "4000000000 0 1 2\n");
        write("face_negative.ply", ply_head + "-1 0 1 2\n");
        // Found by fuzz_ply: an ascii count beyond its declared type (uchar) was cast to an integer (UB).
        std::string uchar_head = ply_head;
        uchar_head.replace(uchar_head.find("list uint int"), 13, "list uchar int");
        write("count_1e28.ply", uchar_head + "1e28 0 1 2\n");
        write("rows_1e18.ply", "ply\nformat ascii 1.0\nelement vertex 1000000000000000000\nproperty float x\nend_header\n0\n");
        write("nan_vertex.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                "nan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
        // Found by fuzz_ply: an empty element without properties (0 bytes a row) divided by zero in the size check.
        write("empty_element.ply", "ply\nformat binary_little_endian 1.0\nelement marker 0\nelement vertex 3\n"
                                   "property float x\nproperty float y\nproperty float z\nelement face 1\n"
                                   "property list uchar int vertex_indices\nend_header\n" +
                                       std::string("\0\0\0\0\0\0\0\0\0\0\0\0"
                                                   "\0\0\x80\x3f\0\0\0\0\0\0\0\0"
                                                   "\0\0\0\0\0\0\x80\x3f\0\0\0\0"
                                                   "\x03\0\0\0\0\x01\0\0\0\x02\0\0\0", 49));
        write("vertex_twice.ply", "ply\nformat ascii 1.0\nelement vertex 0\nelement vertex 3\nproperty float x\n"
                                  "property float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n");
        write("zero_normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n");
        // A .serialized mesh (Mitsuba, version 4) whose zlib stream claims 2^32 - 1 vertices and holds none.
        const std::string claim = std::string("\0\0\0\0mesh\0", 9) + std::string("\xff\xff\xff\xff\0\0\0\0", 8) +
                                  std::string(8, '\0');
        std::string deflated;
        {
            // zlib's stored (uncompressed) block: header 78 01, final block of LEN/NLEN, data, Adler-32.
            std::string z = "\x78\x01\x01";
            const auto n = static_cast<std::uint16_t>(claim.size());
            z += static_cast<char>(n & 0xff);
            z += static_cast<char>(n >> 8);
            z += static_cast<char>(~n & 0xff);
            z += static_cast<char>((~n >> 8) & 0xff);
            z += claim;
            std::uint32_t a = 1, b = 0;
            for (unsigned char c : claim) {
                a = (a + c) % 65521;
                b = (b + a) % 65521;
            }
            const std::uint32_t adler = (b << 16) | a;
            for (int shift = 24; shift >= 0; shift -= 8) z += static_cast<char>((adler >> shift) & 0xff);
            deflated = z;
        }
        write("vertices_4e9.serialized", std::string("\x1c\x04\x04\x00", 4) + deflated + std::string(8, '\0') +
                                             std::string("\x01\x00\x00\x00", 4));
        for (const char* mesh : {"face_4e9.ply", "face_negative.ply", "rows_1e18.ply", "count_1e28.ply", "nan_vertex.ply", "empty_element.ply", "vertex_twice.ply", "zero_normal.obj",
                                 "vertices_4e9.serialized"}) {
            const std::string extension = fs::path(mesh).extension().string();
            const std::string type = extension.substr(1);
            write(std::string("mesh_") + mesh + ".xml",
                  scene("", "", "  <shape type=\"" + type + "\"><string name=\"filename\" value=\"" + mesh + "\"/></shape>\n"));
        }

        // Camera files.
        write("huge_matrix.yml", "%YAML:1.0\n---\nimage_width: 1200\nimage_height: 900\n"
                                 "camera_matrix: !!opencv-matrix\n   rows: 100000\n   cols: 100000\n   dt: d\n"
                                 "   data: [ 1. ]\ndistortion_coefficients: !!opencv-matrix\n   rows: 1\n   cols: 5\n"
                                 "   dt: d\n   data: [ 0., 0., 0., 0., 0. ]\n");

        // Camera files: a good one for a 64 x 48 image, then a matrix that is a string, an infinite focal length and
        // a NaN distortion (undistort used to write a black image and exit 0).
        surfscatter::photo::CameraModel camera;
        camera.image_size = {64, 48};
        camera.matrix = {1010, 0, 31.5, 0, 1010, 23.5, 0, 0, 1};
        camera.distortion = {-0.16, 0.02, 0, 0, 0};
        const fs::path camera_partial = dir() / ("camera.partial." + std::to_string(getpid()) + ".yml");
        surfscatter::photo::write_camera(camera_partial, camera);
        const std::string good_camera = surfscatter::test::read_whole_file(camera_partial.string());
        fs::rename(camera_partial, dir() / "camera.yml");
        const auto camera_variant = [&](const std::string& name, const std::string& from, const std::string& to) {
            std::string text = good_camera;
            const std::size_t at = text.find(from);
            ASSERT_NE(at, std::string::npos) << from << " in\n" << good_camera;
            text.replace(at, from.size(), to);
            write(name, text);
        };
        const std::size_t matrix_at = good_camera.find("camera_matrix:");
        camera_variant("string_matrix.yml",
                       good_camera.substr(matrix_at, good_camera.find("distortion_coefficients:") - matrix_at),
                       "camera_matrix: \"fx 1010\"\n");
        camera_variant("infinite_fx.yml", "1010.", ".Inf");
        camera_variant("nan_distortion.yml", "-1.6000000000000000e-01", ".NaN");
        // Photographs of noise, whole and truncated (half the file ends inside the image data).
        surfscatter::io::Image photo(64, 48, 3);
        std::uint64_t pixel_state = 99;
        for (float& v : photo.pixels) {
            pixel_state = pixel_state * 6364136223846793005ull + 1442695040888963407ull;
            v = static_cast<float>(pixel_state >> 40) * 0x1.0p-24f;
        }
        // EXR photographs (issue 26): a NaN sample, three infinite ones, and every sample near the float maximum.
        const auto exr_variant = [&](const std::string& name, const std::function<void(surfscatter::io::Image&)>& edit) {
            surfscatter::io::Image image = photo;
            edit(image);
            const fs::path whole = dir() / ("whole." + std::to_string(getpid()) + ".exr");
            surfscatter::io::write_exr(whole, image);
            const std::string bytes = surfscatter::test::read_whole_file(whole.string());
            fs::remove(whole);
            write(name, bytes);
        };
        exr_variant("noise.exr", [](surfscatter::io::Image&) {});
        exr_variant("nan_pixel.exr", [](surfscatter::io::Image& i) { i.at(5, 7, 1) = std::nanf(""); });
        exr_variant("inf_pixel.exr", [](surfscatter::io::Image& i) {
            for (int c = 0; c < 3; ++c) i.at(2, 3, c) = INFINITY;
        });
        exr_variant("huge_pixels.exr", [](surfscatter::io::Image& i) {
            for (float& v : i.pixels) v = 1e38f * (0.5f + 0.5f * v);
        });
        // A FIFO where a scene file is expected: opening it blocked until a writer came, maybe forever.
        if (!fs::exists(dir() / "fifo.xml")) mkfifo((dir() / "fifo.xml").c_str(), 0644);
        for (const char* extension : {".png", ".jpg"}) {
            const fs::path whole = dir() / ("whole." + std::to_string(getpid()) + extension);
            surfscatter::io::write_image(whole, photo);
            const std::string bytes = surfscatter::test::read_whole_file(whole.string());
            fs::remove(whole);
            write(std::string("noise") + extension, bytes);
            write(std::string("truncated") + extension, bytes.substr(0, bytes.size() / 2));
        }

        // Chart references (colorcorrect --reference): a NaN value, an id of control bytes, a patch given twice.
        const auto chart = [](const std::string& first_row) {
            std::string text = "IT8.7/2\nBEGIN_DATA_FORMAT\nSAMPLE_ID LAB_L LAB_A LAB_B\nEND_DATA_FORMAT\nBEGIN_DATA\n" +
                               first_row + "\n";
            for (int patch = 1; patch < 24; ++patch)
                text += fmt::format("{}{:02d} {} 1 -1\n", static_cast<char>('A' + patch / 6), patch % 6 + 1, 30 + patch);
            return text + "END_DATA\n";
        };
        write("nan_lab.cie", chart("A01 nan 1 -1"));
        write("control_id.cie", chart("\x1b[31m 30 1 -1"));
        write("patch_twice.cie", chart("A01 30 1 -1\nA01 31 1 -1"));
        // Radiance HDR textures: a header claiming a 60000 x 60000 image, a pixel of 2^128 (beyond float range) after
        // EXPOSURE=0.25, a resolution line of control bytes.
        write("huge.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 60000 +X 60000\n" + std::string(64, '\x02'));
        write("tiny_exposure.hdr", "#?RADIANCE\nEXPOSURE=0.25\n\n-Y 1 +X 1\n\x80\x80\x80\xff");
        write("control_resolution.hdr", "#?RADIANCE\n\n-Y \x1b[2J +X 1\n\x01\x01\x01\x80");
        for (const char* image : {"huge.hdr", "tiny_exposure.hdr", "control_resolution.hdr"})
            write(std::string("bitmap_") + image + ".xml",
                  scene("", std::string("<bsdf type=\"diffuse\"><texture type=\"bitmap\" name=\"reflectance\">"
                                        "<string name=\"filename\" value=\"") + image + "\"/></texture></bsdf>"));

        // Refractive index files.
        fs::create_directories(dir() / "dir.yml");
        fs::create_directories(dir() / "dir.gsf");
        write("pole.yml", "DATA:\n  - type: formula 1\n    wavelength_range: 0.3 1.0\n    coefficients: 0 -1 0.9\n");
        write("binary.csv", std::string("wavelength_nm,n,k\n500,1,\x01\x02\xff\x1b[31m\n", 30));
        write("not_a_directory", "a file\n");

        // Height maps: +-1e308 heights, white noise (no KC fit), and a real map for --surface.
        std::string huge = "0 1 2 3 4 5 6 7\n";
        for (int row = 0; row < 7; ++row) huge += row == 3 ? "1 2 3 1e308 -1e308 6 7 8\n" : "1 2 3 4 5 6 7 8\n";
        write("huge_heights.txt", huge);
        std::string noise;
        std::uint64_t state = 12345;
        for (int row = 0; row < 64; ++row) {
            for (int col = 0; col < 64; ++col) {
                state = state * 6364136223846793005ull + 1442695040888963407ull;
                noise += std::to_string(static_cast<double>(state >> 11) * 0x1.0p-53 - 0.5) + (col < 63 ? " " : "\n");
            }
        }
        write("white_noise.txt", noise);
        std::vector<double> heights(64 * 64);
        for (std::size_t i = 0; i < heights.size(); ++i) heights[i] = 0.01 * std::sin(0.3 * static_cast<double>(i % 64));
        const fs::path gsf_partial = dir() / ("h.partial." + std::to_string(getpid()) + ".gsf");
        surfscatter::heightmap::write_gsf(surfscatter::heightmap::HeightMap(64, 64, 0.1, 0.1, heights), gsf_partial);
        fs::rename(gsf_partial, dir() / "h.gsf");
        // Found by fuzz_x3p: a value with a line break in main.xml was quoted raw (two lines of message).
        const fs::path x3p_partial = dir() / ("line_break.partial." + std::to_string(getpid()) + ".x3p");
        surfscatter::test::write_zip(
            x3p_partial,
            {{"main.xml",
              "<?xml version=\"1.0\"?>\n<p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\"><Record1>"
              "<Revision>ISO5436 - 2000</Revision><FeatureType>SUR</FeatureType><Axes>"
              "<CX><AxisType>I</AxisType><DataType>D</DataType><Increment>1e\n06</Increment><Offset>0</Offset></CX>"
              "<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>1e-6</Increment><Offset>0</Offset></CY>"
              "<CZ><AxisType>A</AxisType><DataType>D</DataType></CZ></Axes></Record1><Record3><MatrixDimension>"
              "<SizeX>2</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ></MatrixDimension><DataList><Datum>0</Datum>"
              "<Datum>1e-9</Datum><Datum>2e-9</Datum><Datum>0</Datum></DataList></Record3></p:ISO5436_2>\n"}});
        fs::rename(x3p_partial, dir() / "line_break.x3p");

        // Study files (docs/DISTRIBUTED.md).
        const std::string albedo_only = R"("wavelengths": [500], "albedo": {"theta_i": [0]})";
        write("study_truncated.json", R"({"models": [{"name": "a", "model": "ghs"})");
        write("study_unknown_key.json", R"({"models": [{"name": "a", "model": "ghs"}], )" + albedo_only + R"(, "colour": 1})");
        write("study_name_path.json", R"({"models": [{"name": "../a", "model": "ghs"}], )" + albedo_only + "}");
        write("study_name_twice.json",
              R"({"models": [{"name": "a", "model": "ghs"}, {"name": "a", "model": "ggx_stats"}], )" + albedo_only + "}");
        write("study_theta_90.json", R"({"models": [{"name": "a", "model": "ghs"}], "wavelengths": [500], "albedo": {"theta_i": [90]}})");
        write("study_focus_huge.json",
              R"({"models": [{"name": "a", "model": "ghs"}], "scene": "ok.xml", "views": [1],
                  "render": {"crop": {"focus": [1e300, 0, 0], "radius": 1}}})");
        write("study_nested.json", R"({"models": )" + nested("[", "]", "", 100000) + "}");
        write_rule_files();
    }
};

const std::string kLongName = std::string(300, 'a') + ".yml";
const std::vector<std::string> kBrdf = {"--material", "Au", "--wavelength", "550", "--theta-i", "30"};
const std::vector<std::string> kKc = {"--psd", "kc", "--sigma", "0.05", "--corr-length", "2", "--gamma", "3"};

std::vector<std::string> join(std::vector<std::string> a, const std::vector<std::string>& b,
                              const std::vector<std::string>& c = {}) {
    a.insert(a.end(), b.begin(), b.end());
    a.insert(a.end(), c.begin(), c.end());
    return a;
}

std::vector<std::string> render(const std::string& scene_file, std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {"render", "@D@/" + scene_file, "--quiet", "-o", "@D@/out.exr"};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
}

// Photo commands on files of the scratch directory (the image is read after the camera file and the options).
std::vector<std::string> undistort(const std::string& camera, const std::string& image = "truncated.png") {
    return {"undistort", "@D@/" + image, "--camera", "@D@/" + camera, "-o", "@D@/u.png"};
}

std::vector<std::string> pose(const std::string& camera) {
    return {"pose", "@D@/truncated.png", "--camera", "@D@/" + camera, "--marker-length", "0.05", "-o", "@D@/u.json"};
}

std::vector<std::string> colorcorrect(const std::string& reference) {
    return {"colorcorrect", "@D@/noise.png", "--reference", "@D@/" + reference, "-o", "@D@/cc.png", "--ccm",
            "@D@/cc.json"};
}

std::vector<std::string> calibrate(const std::string& squares) {
    return {"calibrate", "@D@/truncated.png", "@D@/truncated.png", "@D@/truncated.png", "--squares", squares,
            "--square-length", "0.03", "--marker-length", "0.022", "-o", "@D@/c.yml"};
}

const std::vector<HostileCase> kCases = {
    // Crashes.
    {"ThreadsHundredThousand", render("ok.xml", {"--threads", "100000"}), 2, "--threads must be between 1 and 256"},
    {"StudyDevZero", {"study", "/dev/zero"}, 2, "study file /dev/zero is not a regular file"},
    {"StudyDirectory", {"study", "@D@/dir.yml"}, 2, "study file @D@/dir.yml is a directory"},
    {"StudyTruncated", {"study", "@D@/study_truncated.json"}, 2, "@D@/study_truncated.json: not valid JSON"},
    {"StudyUnknownKey", {"study", "@D@/study_unknown_key.json"}, 2, "@D@/study_unknown_key.json: unknown key 'colour'"},
    {"StudyNameIsAPath", {"study", "@D@/study_name_path.json"}, 2,
     "models[0].name: name '../a' may only hold letters, digits, '_', '-' and '.'"},
    {"StudyNameTwice", {"study", "@D@/study_name_twice.json"}, 2, "models[1].name: 'a' is used twice"},
    {"StudyTheta90", {"study", "@D@/study_theta_90.json"}, 2, "albedo.theta_i[0]: must be in [0, 90) degrees, got 90"},
    {"StudyFocusHuge", {"study", "@D@/study_focus_huge.json"}, 2, "render.crop.focus[0]: must be within +-1e+15"},
    {"StudyNested", {"study", "@D@/study_nested.json"}, 2, "@D@/study_nested.json: arrays and objects nested more than 64 deep"},
    {"StudyThreads", {"study", "@D@/study_theta_90.json", "--threads", "100000"}, 2, "--threads must be between 1 and 256"},
    {"TwosidedNested30000Deep", render("twosided_30000.xml"), 2, "twosided_30000.xml:10: elements nested more than 64 deep"},
    {"CheckerboardNested30000Deep", render("checker_30000.xml"), 2, "checker_30000.xml:10: elements nested more than 64 deep"},
    // Hangs.
    {"GammaBillion", join({"brdf", "eval", "--model", "ghs", "--psd", "kc", "--sigma", "0.05", "--corr-length", "2",
                           "--gamma", "1e9", "--theta-o", "0"}, kBrdf),
     2, "gamma must be between 1.01 and 100"},
    // Internal errors.
    {"DirectoryAsYml", {"ior", "--material", "@D@/dir.yml", "--wavelength", "500"}, 2, "@D@/dir.yml is a directory"},
    {"DirectoryAsGsf", {"surface", "fit", "@D@/dir.gsf"}, 2, "@D@/dir.gsf is a directory"},
    {"MetalsOutIsAFile", {"metals", "--no-plot", "--out", "@D@/not_a_directory"}, 2,
     "--out @D@/not_a_directory exists and is not a directory"},
    {"SynthSizeMillion", {"surface", "synth", "--sigma", "1", "--corr-length", "1", "--gamma", "3", "--size", "1000000",
                          "--spacing", "0.1", "-o", "@D@/big.gsf"},
     2, "a 1000000 x 1000000 surface needs"},
    {"FilmMillionSquared", render("ok.xml", {"-D", "size=1000000"}), 2, "ok.xml:6: film must be between 1x1 and 65536x65536"},
    {"FilmBeyondMemory", render("ok.xml", {"-D", "size=65536"}), 2, "a 65536x65536 film needs"},
    {"PlyFaceCount4e9", render("mesh_face_4e9.ply.xml"), 2, "face_4e9.ply: a list claims 4000000000 items"},
    {"PlyFaceCountNegative", render("mesh_face_negative.ply.xml"), 2, "face_negative.ply: -1 in a list count does not fit its type (range 0 to 4.29497e+09)"},
    {"PlyRows1e18", render("mesh_rows_1e18.ply.xml"), 2, "claims 1000000000000000000 items"},
    {"PlyAsciiCountBeyondItsType", render("mesh_count_1e28.ply.xml"), 2,
     "count_1e28.ply: 1e28 in a list count does not fit its type (range 0 to 255)"},
    {"FileNameTooLong", {"ior", "--material", "@D@/" + kLongName, "--wavelength", "500"}, 2, "File name too long"},
    {"GammaHuge", join({"brdf", "eval", "--model", "ghs", "--psd", "kc", "--sigma", "0.05", "--corr-length", "2",
                        "--gamma", "1e308", "--theta-o", "0"}, kBrdf),
     2, "gamma must be between 1.01 and 100 (KC), got 1e+308"},
    {"IncludeDevZero", render("include_zero.xml"), 2, "include_zero.xml:2: file /dev/zero is not a regular file"},
    // NaN or Inf written with exit 0.
    {"ExposureOption", render("ok.xml", {"--exposure", "2000"}), 2, "--exposure must be between -64 and 64 stops, got 2000"},
    {"ExposureInFilm", render("film_exposure.xml"), 2, "film_exposure.xml:6: exposure must be between -64 and 64 stops"},
    {"ExposureDefine", render("ok.xml", {"-D", "exposure=2000"}), 2, "ok.xml:6: exposure must be between -64 and 64 stops"},
    {"RgbRadiance1e300", render("rgb_huge.xml"), 2, "rgb_huge.xml:10: RGB values must be between 0 and 1e+30"},
    {"PsdCorrLength1e300", {"psd", "--sigma", "1", "--corr-length", "1e300", "--gamma", "3", "--zeta", "0,1"}, 2,
     "--corr-length must be between 1e-09 and 1e+09 um, got 1e+300"},
    {"SelfconvGammaNearOne", {"selfconv", "--gamma", "1.000000000001", "--corr-length", "1", "--orders", "13"}, 2,
     "--gamma must be between 1.01 and 100"},
    // Silently accepted or ignored.
    {"EmptyWavelengthItem", {"ior", "--material", "Au", "--wavelength", "400,,500"}, 2, "--wavelength: item 2 of '400,,500' is empty"},
    {"EmptyThetaItem", {"fresnel", "--material", "Au", "--wavelength", "500", "--theta", "0,,45"}, 2, "--theta: item 2 of '0,,45' is empty"},
    {"EmptyModelsItem", join({"brdf", "slice", "--models", "ggx,,ghs", "--alpha", "0.1", "--csv", "@D@/s.csv"}, kBrdf), 2,
     "--models: item 2 of 'ggx,,ghs' is empty"},
    {"TrailingComma", {"ior", "--material", "Au", "--wavelength", "400,"}, 2, "--wavelength: item 2 of '400,' is empty"},
    {"EmptyLookatItem", render("lookat_empty.xml"), 2, "lookat_empty.xml:2: origin: item 2 of '0,, -1.6, 0.9' is empty"},
    {"EmptyRgbItem", render("rgb_empty.xml"), 2, "rgb_empty.xml:10: rgb: item 2 of '0.2,,0.5' is empty"},
    {"SmoothingWithGgx", join({"brdf", "eval", "--model", "ggx_stats", "--alpha", "0.1", "--smoothing", "5", "--theta-o", "0"}, kBrdf),
     2, "--smoothing does not apply to --model ggx_stats: used with alpha_from smoothed only"},
    {"AlphaWithGhs", join({"brdf", "eval", "--model", "ghs", "--alpha", "0.3", "--theta-o", "0"}, kKc, kBrdf), 2,
     "--alpha does not apply to --model ghs"},
    {"CutoffWithoutTwoScale", join({"brdf", "albedo", "--model", "ghs", "--cutoff-wavelengths", "50"}, kKc, kBrdf), 2,
     "--cutoff-wavelengths does not apply to --model ghs: used by model two_scale only"},
    {"EpsilonWithoutPoissonMass", join({"brdf", "albedo", "--model", "ghs", "--method", "refit", "--epsilon", "1e-3"}, kKc, kBrdf),
     2, "--epsilon does not apply to --model ghs: used by model ghs with method refit and truncation poisson_mass only"},
    {"SigmaWithSurfaceFile", join({"brdf", "albedo", "--model", "ghs", "--surface", "@D@/h.gsf", "--sigma", "0.3"}, kBrdf), 2,
     "--sigma does not apply to --model ghs: a height map gives its own statistics (psd file or measured)"},
    {"FresnelWithGgx", join({"brdf", "eval", "--model", "ggx_stats", "--alpha", "0.1", "--fresnel", "half", "--theta-o", "0"}, kBrdf),
     2, "--fresnel does not apply to --model ggx_stats"},
    {"SmoothingInMeasuredGgxScene", render("ggx_stats_smoothing.xml"), 2,
     "ggx_stats_smoothing.xml:10: parameter 'smoothing' does not apply to bsdf 'ggx_stats': used with alpha_from smoothed only"},
    {"RenormalizationInSsaScene", render("ghs_ssa_renormalization.xml"), 2,
     "ghs_ssa_renormalization.xml:10: parameter 'renormalization' does not apply to bsdf 'ghs_ssa'"},
    {"RenderSeedNegative", render("ok.xml", {"--seed", "-5"}), 2, "--seed must be >= 0, got -5"},
    {"RenderSppZero", render("ok.xml", {"--spp", "0"}), 2, "--spp must be positive, got 0"},
    {"UnusedDefine", render("ok.xml", {"-D", "sigmaa=0.3"}), 2, "-D sigmaa=0.3: the scene @D@/ok.xml never uses $sigmaa"},
    {"DefineTwice", render("ok.xml", {"-D", "size=4", "-D", "size=5"}), 2, "-D size is given twice"},
    {"SynthSeedNegative", {"surface", "synth", "--sigma", "1", "--corr-length", "1", "--gamma", "3", "--size", "16",
                           "--spacing", "0.1", "--seed", "-1", "-o", "@D@/s.gsf"},
     2, "--seed must be >= 0, got -1"},
    {"TextInsideFloat", render("float_text.xml"), 2, "float_text.xml:13: <float> cannot contain text, got 'hello'"},
    {"ChildInsideTranslate", render("translate_child.xml"), 2, "translate_child.xml:10: <translate> cannot contain elements, got <scale>"},
    {"TextInsideShape", render("shape_text.xml"), 2, "shape_text.xml:10: unexpected text 'stray words' inside <shape>"},
    {"TextOutsideScene", render("text_outside.xml"), 2, "text_outside.xml:2: unexpected text 'trailing words' outside <scene>"},
    {"TwoRootElements", render("two_roots.xml"), 2, "a second root element <scene>"},
    {"FocusRadiusNegative", {"compare-models", "--focus-radius", "-1", "-o", "@D@/cmp"}, 2, "--focus-radius must be >= 0, got -1"},
    {"FocusWithoutRadius", {"compare-models", "--focus", "0,0,0", "--focus-radius", "0", "-o", "@D@/cmp"}, 2,
     "--focus does not apply with --focus-radius 0"},
    {"CompareModelsDefineTheyOwn", {"compare-models", "-D", "model=ghs", "-o", "@D@/cmp"}, 2,
     "-D model: compare-models sets this parameter itself"},
    // Bad messages.
    {"BlackbodyScaleNegative", render("blackbody_negative.xml"), 2,
     "blackbody_negative.xml:14: blackbody scale must be between 0 and 1e+30, got -1"},
    {"ConstantSpectrumNegative", render("spectrum_negative.xml"), 2,
     "spectrum_negative.xml:10: spectrum value must be between 0 and 1e+30, got -1"},
    {"FilmWhiteBalanceUnknown", render("film_white_balance.xml"), 2, "film_white_balance.xml:6: white_balance 'foo'"},
    {"CorrLengthDefine1e308", render("ghs.xml", {"-D", "corr_length=1e308"}), 2,
     "ghs.xml:10: bsdf 'ghs': corr_length must be between 1e-09 and 1e+09 um, got 1e+308"},
    {"HeightsPlusMinus1e308", {"surface", "fit", "@D@/huge_heights.txt", "--spacing", "0.1"}, 2,
     "height at column 3, row 4 is 1e+308 um (every height must be finite and within +-1e+09 um)"},
    {"Smoothing1e300", {"surface", "fit", "@D@/h.gsf", "--smoothing", "1e300"}, 2,
     "--smoothing 1e+300 um is wider than the 6.4 x 6.4 um map"},
    {"MetalsTemperature1e300", {"metals", "--no-plot", "--temperature", "1e300", "--out", "@D@/metals"}, 2,
     "--temperature must be in (0, 1e+09] K, got 1e+300"},
    {"WhiteBalance1e300", render("ok.xml", {"--white-balance", "1e300"}), 2,
     "--white-balance: white_balance '1e300': white balance temperature must be in (0, 1e+09] K"},
    {"FitFailsOnWhiteNoise", {"surface", "fit", "@D@/white_noise.txt", "--spacing", "0.1"}, 2, "KC fit:"},
    {"FocusNan", {"compare-models", "--focus", "nan,0,0", "-o", "@D@/cmp"}, 2, "--focus: 'nan' is not a finite number"},
    {"EmptyWavelength", {"fresnel", "--material", "Au", "--wavelength", "", "--theta", "0"}, 2, "--wavelength: empty value"},
    {"FormulaPoleNamesFile", {"ior", "--material", "@D@/pole.yml", "--wavelength", "950"}, 2,
     "@D@/pole.yml: DATA entry 1: formula 1 gives no real positive index at 0.95 um"},
    {"BinaryCsvNotEchoedRaw", {"ior", "--material", "@D@/binary.csv", "--wavelength", "500"}, 2,
     "got '500,1,\\x01\\x02\\xff\\x1b[3"},
    {"UnknownSubcommand", {"rendr", "x.xml"}, 2, "unknown subcommand 'rendr' of surfscatter (known: acv, board, brdf,"},
    {"UnknownNestedSubcommand", {"surface", "fitt", "h.gsf"}, 2, "unknown subcommand 'fitt' of surfscatter surface"},
    // Added: more of the same kinds.
    {"PlyNanVertex", render("mesh_nan_vertex.ply.xml"), 2, "nan_vertex.ply: 'nan' in a property is not a finite number"},
    {"ObjZeroNormal", render("mesh_zero_normal.obj.xml"), 2, "zero_normal.obj:4: normal (0, 0, 0) has no direction"},
    {"SerializedVertices4e9", render("mesh_vertices_4e9.serialized.xml"), 2, "vertices_4e9.serialized: mesh 0 data ends early"},
    {"IncludeCycle", render("include_self.xml"), 2, "include_self.xml:2: includes nested more than 16 deep"},
    {"IntegerTooLarge", render("integer_huge.xml"), 2, "integer_huge.xml:7: crop_width: '10000000000' is not an integer"},
    {"TransformOverflow", render("matrix_huge.xml"), 2, "matrix_huge.xml:10: the transform reaches 1e+200 (beyond the +-1e+15 a scene may span)"},
    {"SphereRadius1e300", render("sphere_huge.xml"), 2, "sphere_huge.xml:13: shape 'sphere': the shape's bounding box corner (-inf, -inf, -inf) is not finite"},
    {"ThreadsNegative", render("ok.xml", {"--threads", "-1"}), 2, "--threads must be between 1 and 256"},
    {"DefineNameInvalid", render("ok.xml", {"-D", "a-b=1"}), 2, "-D a-b: a parameter name has letters, digits and '_' only"},
    {"SppNotANumber", render("ok.xml", {"--spp", "1.5"}), 2, "--spp"},
    {"GgxAlphaHuge", join({"brdf", "eval", "--model", "ggx_stats", "--alpha", "1e300", "--theta-o", "0"}, kBrdf), 2,
     "alpha must be between 0.0001 and 100, got 1e+300"},
    {"GgxAlphaTiny", join({"brdf", "eval", "--model", "ggx_stats", "--alpha", "1e-300", "--theta-o", "0,30"}, kBrdf), 2,
     "alpha must be between 0.0001 and 100, got 1e-300"},
    {"GgxSmoothing1e300", join({"brdf", "eval", "--model", "ggx_stats", "--alpha-from", "smoothed", "--smoothing", "1e300",
                                "--theta-o", "0"}, kKc, kBrdf),
     2, "smoothing must be between 1e-09 and 1e+09 um, got 1e+300"},
    {"EvalWavelengthOutsideData", {"brdf", "eval", "--model", "ggx_stats", "--alpha", "0.1", "--material", "Au",
                                   "--wavelength", "100", "--theta-i", "30", "--theta-o", "0"},
     2, "wavelength 100 nm is outside the range"},
    // Findings of the fuzz targets (their inputs are in fuzz/corpus/<target>/regression-*).
    {"FuzzHeightMapWithoutRings", {"surface", "fit", "@S@/fuzz/corpus/height_map/regression-anisotropic-spacing-no-ring"},
     2, "KC fit: only 0 PSD rings"},
    {"FuzzCameraMatrixAllocation", {"undistort", "@D@/any.png", "--camera",
                                    "@S@/fuzz/corpus/camera_file/regression-malformed-matrix-48GB-allocation.yml", "-o",
                                    "@D@/undistorted.png"},
     2, "must be an OpenCV matrix"},
    {"CalibrateSquares65536", calibrate("65536x65536"), 2, "--squares must be between 3 and 200 per side, got 65536"},
    {"CalibrateSquaresOverflow", calibrate("100000x100000"), 2, "--squares must be between 3 and 200 per side, got 100000"},
    {"CalibrateSquaresIntMax", calibrate("3x2147483647"), 2, "--squares must be between 3 and 200 per side, got 2147483647"},
    {"CalibrateSquaresBeyondInt", calibrate("99999999999x7"), 2, "--squares '99999999999x7' must be WxH with whole numbers"},
    {"CameraMatrixString", undistort("string_matrix.yml"), 2,
     "camera file '@D@/string_matrix.yml': 'camera_matrix' must be an OpenCV matrix"},
    {"CameraMatrixStringPose", pose("string_matrix.yml"), 2,
     "camera file '@D@/string_matrix.yml': 'camera_matrix' must be an OpenCV matrix"},
    {"CameraFocalLengthInfinite", undistort("infinite_fx.yml"), 2,
     "camera file '@D@/infinite_fx.yml': camera_matrix entry (0, 0) is inf, not a finite number"},
    {"CameraFocalLengthInfinitePose", pose("infinite_fx.yml"), 2,
     "camera file '@D@/infinite_fx.yml': camera_matrix entry (0, 0) is inf, not a finite number"},
    {"CameraDistortionNan", undistort("nan_distortion.yml"), 2,
     "camera file '@D@/nan_distortion.yml': distortion_coefficients entry (0, 0) is -nan"},
    {"CameraDistortionNanPose", pose("nan_distortion.yml"), 2,
     "camera file '@D@/nan_distortion.yml': distortion_coefficients entry (0, 0) is -nan"},
    {"CameraFileIsADirectory", undistort("dir.yml"), 2, "camera file '@D@/dir.yml' is a directory"},
    {"UndistortTruncatedPng", undistort("camera.yml"), 2, "image '@D@/truncated.png' could not be decoded"},
    {"UndistortTruncatedJpeg", undistort("camera.yml", "truncated.jpg"), 2, "image '@D@/truncated.jpg' is truncated"},
    {"FuzzTiffSamplesAllocation", {"undistort", "@S@/fuzz/corpus/raster_image/regression-tiff-strip-allocation.tif",
                                   "--camera", "@D@/camera.yml", "-o", "@D@/u.png"},
     2, "a 7x12037 TIFF image of 57089 16-bit samples a pixel (9620524102 bytes) is more than its 222 bytes can hold"},
    {"FuzzTiffTileAllocation", {"undistort", "@S@/fuzz/corpus/raster_image/regression-tiff-tile-allocation.tif",
                                "--camera", "@D@/camera.yml", "-o", "@D@/u.png"},
     2, "a 65031x65321 TIFF tile is more than the file's 222 bytes can hold"},
    {"FuzzTiffMessageLineBreak", {"undistort", "@S@/fuzz/corpus/raster_image/regression-tiff-message-line-break.tif",
                                  "--camera", "@D@/camera.yml", "-o", "@D@/u.png"},
     2, "Tag InkNames:\\x0a  Value 1 of NumberOfInks is different from the SamplesPerPixel value 2"},
    {"FuzzCameraFileOpenCvLengthError", {"undistort", "@D@/any.png", "--camera",
                                         "@S@/fuzz/corpus/camera_file/regression-damaged-key-length-error.yml", "-o",
                                         "@D@/undistorted.png"},
     2, "regression-damaged-key-length-error.yml' is not valid YAML/XML/JSON (OpenCV's parser failed: basic_string::_M_create)"},
    {"FuzzCameraFileOpenCvNeverReturns", {"undistort", "@D@/any.png", "--camera",
                                          "@S@/fuzz/corpus/camera_file/regression-opencv-parser-endless-loop.yml", "-o",
                                          "@D@/undistorted.png"},
     2, "is not valid YAML/XML/JSON: OpenCV's parser does not finish on it (stopped after 10 s)"},
    {"CameraMatrixTooLarge", undistort("huge_matrix.yml"), 2,
     "'camera_matrix' is 100000 x 100000, larger than any camera matrix"},
    {"FuzzPlyEmptyElementWithoutProperties", render("mesh_empty_element.ply.xml", {"--spp", "1"}), 0, ""},
    {"PlyElementDeclaredTwice", render("mesh_vertex_twice.ply.xml"), 2,
     "vertex_twice.ply:4: element 'vertex' is declared twice"},
    {"FuzzX3pLineBreakInValue", {"surface", "fit", "@D@/line_break.x3p"}, 2,
     "main.xml: Record1/Axes/CX/Increment = '1e\\x0a06' is not a finite number"},
    {"ChartReferenceNan", colorcorrect("nan_lab.cie"), 2, "nan_lab.cie:6: LAB_L 'nan' is not a finite number"},
    {"ChartReferenceControlBytes", colorcorrect("control_id.cie"), 2,
     "control_id.cie:6: sample id '\\x1b[31m' is not one of A01..D06"},
    {"ChartReferencePatchTwice", colorcorrect("patch_twice.cie"), 2, "patch_twice.cie:7: sample A01 is given twice"},
    {"HdrHeaderClaimsHugeImage", render("bitmap_huge.hdr.xml"), 2,
     "huge.hdr: a 60000x60000 HDR image needs at least 14400000000 bytes of pixel data, the file holds 64"},
    {"HdrTinyExposure", render("bitmap_tiny_exposure.hdr.xml"), 2,
     "tiny_exposure.hdr: pixel (0, 0) is 3.402823669209385e+38 after dividing by the EXPOSURE 0.25: beyond the float range"},
    {"HdrControlBytesInResolution", render("bitmap_control_resolution.hdr.xml"), 2,
     "unsupported HDR resolution line '-Y \\x1b[2J +X 1'"},
    // Huge but valid: a finite, correct answer.
    {"ThreadsAtLimit", render("ok.xml", {"--threads", "256", "--spp", "1"}), 0, ""},
    {"PsdExtremeButValid", {"psd", "--sigma", "1e9", "--corr-length", "1e9", "--gamma", "100", "--zeta", "0,1e-9,1,1e300"}, 0, ""},
    {"AcvSmallGammaValid", {"acv", "--sigma", "1e-9", "--corr-length", "1e-9", "--gamma", "1.01", "--r", "0,1e-300,1,1e300"}, 0, ""},
    {"MetalsHotLamp", {"metals", "--no-plot", "--temperature", "1e9", "--out", "@D@/metals_hot"}, 0, ""},

    // Issue 26, rules on numbers and writes (docs/RELIABILITY.md "Numbers and writes").
    // Every printed number is finite or the input is refused (format_number is the net; the sources are fixed too).
    {"AcvSubnormalR", {"acv", "--sigma", "1", "--corr-length", "1", "--gamma", "3", "--r", "1e-320,1e-310"}, 0, ""},
    {"GgxKcLinkWavelength1e300", join({"brdf", "eval", "--model", "ggx_stats", "--alpha-from", "kc_link", "--material",
                                       "perfect", "--wavelength", "1e-300", "--theta-i", "30", "--theta-o", "30"}, kKc),
     2, "alpha_from kc_link gives alpha = 0 at wavelength 1e-300 nm (correlation length 2 um), below GGX's 0.0001"},
    {"GgxKcLinkWavelength1e100", join({"brdf", "eval", "--model", "ggx_stats", "--alpha-from", "kc_link", "--material",
                                       "perfect", "--wavelength", "1e-100", "--theta-i", "30", "--theta-o", "30"}, kKc),
     2, "at wavelength 1e-100 nm (correlation length 2 um), below GGX's 0.0001"},
    // Non-finite pixels of input images are refused, in the one float reader of photographs.
    {"UndistortNanExr", undistort("camera.yml", "nan_pixel.exr"), 2,
     "nan_pixel.exr': 1 samples are not finite (the first, at pixel (5, 7), is nan)"},
    {"CompareInfExr", {"compare", "@D@/inf_pixel.exr", "@D@/noise.exr", "-o", "@D@/cmp_inf.png"}, 2,
     "inf_pixel.exr': 3 samples are not finite (the first, at pixel (2, 3), is inf)"},
    {"CompareInfRender", {"compare", "@D@/noise.exr", "@D@/inf_pixel.exr", "-o", "@D@/cmp_inf.png"}, 2,
     "inf_pixel.exr': 3 samples are not finite"},
    {"ColorcorrectNanExr", {"colorcorrect", "@D@/nan_pixel.exr", "-o", "@D@/cc_nan.exr", "--ccm", "@D@/cc_nan.json"}, 2,
     "nan_pixel.exr': 1 samples are not finite"},
    {"CompareHugePixels", {"compare", "@D@/huge_pixels.exr", "@D@/noise.exr", "-o", "@D@/cmp_huge.png"}, 0, ""},
    // Every write is checked: stdout on a full device, files on a full disk (no partial file left).
    {"IorStdoutFull", {"ior", "--material", "Au", "--wavelength", "400,500,600"}, 2,
     "could not write the standard output: No space left on device", "", "/dev/full"},
    {"PsdStdoutFull", {"psd", "--sigma", "1", "--corr-length", "1", "--gamma", "3", "--zeta", "0,1,2"}, 2,
     "could not write the standard output: No space left on device", "", "/dev/full"},
    {"BrdfSampleStdoutFull", join({"brdf", "sample", "--model", "ggx_stats", "--alpha", "0.3"}, kBrdf, {"--count", "10"}), 2,
     "could not write the standard output: No space left on device", "", "/dev/full"},
    {"BrdfAlbedoStdoutFull", join({"brdf", "albedo", "--model", "ggx_stats", "--alpha", "0.3"}, kBrdf), 2,
     "could not write the standard output: No space left on device", "", "/dev/full"},
    {"MetalsStdoutFull", {"metals", "--no-plot", "--out", "@D@/metals_stdout_full"}, 2,
     "could not write the standard output: No space left on device", "", "/dev/full"},
    {"MetalsCsvDiskFull", {"metals", "--no-plot", "--out", "@D@/metals_disk_full"}, 2,
     "cannot write @D@/metals_disk_full/metals_reflectance.csv: File too large", "trap '' XFSZ; ulimit -f 16; ", "",
     "@D@/metals_disk_full/metals_reflectance.csv"},
    {"CompareCsvCannotBeWritten", {"compare", "@D@/noise.exr", "@D@/noise.exr", "-o", "@D@/compare_csv_dir/sheet.png"}, 2,
     "-o's CSV @D@/compare_csv_dir/sheet.csv is a folder: name a file in it", "mkdir -p '@D@/compare_csv_dir/sheet.csv'; "},
    // Special files are refused wherever a file is opened (the table cache: tests/core/test_input.cpp).
    {"SceneIsAFifo", render("fifo.xml"), 2, "@D@/fifo.xml is a FIFO (named pipe), not a file"},
};

// Issue 26, rules 4 and 7: a row per class. Exit 2 cases of this block print exactly one line (no info line before
// the error either).
const std::vector<HostileCase> kRuleCases = {
    // Conflicts are errors naming both places.
    {"IntegratorTwice", render("integrator_twice.xml"), 2,
     "integrator_twice.xml:14: <integrator> is given twice (the first at @D@/integrator_twice.xml:13)"},
    {"DefaultTwiceDifferentValues", render("default_conflict.xml"), 2,
     "default_conflict.xml:4: <default name=\"size\"> is given twice with different values ('16' here, '8' at "
     "@D@/default_conflict.xml:2)"},
    {"DefaultTwiceSameValue", render("default_repeated.xml", {"--spp", "1"}), 0, ""},
    {"SamplerTwice", render("sampler_twice.xml"), 2,
     "sampler_twice.xml:9: a sensor's <sampler> is given twice (the first at @D@/sampler_twice.xml:8)"},
    {"ShapeTwoBsdfs", render("shape_two_bsdfs.xml"), 2,
     "shape_two_bsdfs.xml:11: a shape's <bsdf> is given twice (the first at @D@/shape_two_bsdfs.xml:10)"},
    {"GsfKeyTwice", {"surface", "info", "@D@/xres_twice.gsf"}, 2,
     "xres_twice.gsf:4: header field 'XRes' is given twice (first at line 2)"},
    {"StudyKeyTwice", {"study", "@D@/study_key_twice.json"}, 2,
     "study_key_twice.json:4: key 'wavelengths' is given twice in one object (first at line 2)"},
    {"StudyNestedKeyTwice", {"study", "@D@/study_model_key_twice.json"}, 2,
     "study_model_key_twice.json:2: key 'model' is given twice in one object (first at line 1)"},
    {"ManifestKeyTwice", {"study", "@D@/manifest_twice/study.json"}, 2,
     "manifest.json:3: key 'jobs' is given twice in one object (first at line 2); move it away"},
    {"YamlKeyTwice", {"ior", "--material", "@D@/data_twice.yml", "--wavelength", "500"}, 2,
     "data_twice.yml:6: key 'DATA' is given twice in one mapping (first at line 1)"},
    // Every parsed object is checked, referenced or not.
    {"UnreferencedUnknownBsdf", render("unreferenced_foobar.xml"), 2, "unreferenced_foobar.xml:13: unknown bsdf plugin 'foobar'"},
    {"UnreferencedTextureBadParameter", render("unreferenced_bad_parameter.xml"), 2,
     "unreferenced_bad_parameter.xml:13: unknown parameter 'colour0' of texture 'checkerboard'"},
    // Values out of the physical domain are refused.
    {"SpectrumWavelengthNegative", render("spectrum_wavelength_negative.xml"), 2,
     "spectrum_wavelength_negative.xml:10: spectrum wavelength -5 nm is not positive"},
    {"SpdWavelengthZero", render("spd_wavelength_zero.xml"), 2,
     "spd_wavelength_zero.xml:10: spectrum wavelength 0 nm is not positive"},
    {"YamlNegativeN", {"ior", "--material", "@D@/negative_n.yml", "--wavelength", "500"}, 2,
     "negative_n.yml:5: n = -1 is negative"},
    {"YamlTabulatedKNegative", {"ior", "--material", "@D@/negative_k_only.yml", "--wavelength", "500"}, 2,
     "negative_k_only.yml:9: k = -2 is negative"},
    {"CsvNegativeN", {"ior", "--material", "@D@/negative_n.csv", "--wavelength", "500"}, 2,
     "negative_n.csv:3: n = -0.5 is negative"},
    {"YamlSubnormalWavelength", {"ior", "--material", "@D@/subnormal_wavelength.yml", "--wavelength", "500"}, 2,
     "subnormal_wavelength.yml:4: '1e-320' is too small (subnormal"},
    {"StudyNumber1e400", {"study", "@D@/study_number_1e400.json"}, 2,
     "study_number_1e400.json:2: number '1e400' is beyond the range of a double"},
    {"SeedBeyondInt64", render("ok.xml", {"--seed", "99999999999999999999"}), 2,
     "--seed: '99999999999999999999' is beyond the 64-bit integer range"},
    {"SppBeyondInt64", render("ok.xml", {"--spp", "-99999999999999999999"}), 2,
     "--spp: '-99999999999999999999' is beyond the 64-bit integer range"},
    {"CountBeyondInt64", join({"brdf", "sample", "--model", "ggx", "--alpha", "0.1", "--count", "99999999999999999999"}, kBrdf),
     2, "--count: '99999999999999999999' is beyond the 64-bit integer range"},
    {"CountHexBeyondInt64", join({"brdf", "sample", "--model", "ggx", "--alpha", "0.1", "--count", "0x1ffffffffffffffff"}, kBrdf),
     2, "--count: '0x1ffffffffffffffff' is beyond the 64-bit integer range"},
    // Messages: one line, names escaped, library failures named.
    {"BrdfSurfaceFailsInOneLine", join({"brdf", "eval", "--model", "ghs", "--surface", "@D@/white_noise.gsf", "--theta-o", "0"}, kBrdf),
     2, "KC fit:"},
    {"NameWithLineBreak", {"ior", "--material", "@D@/two\nlines.yml", "--wavelength", "500"}, 2,
     "refractive index file not found: @D@/two\\x0alines.yml"},
    {"ColorcorrectSimplexOnNoise", {"colorcorrect", "@D@/noise.png", "--chart-corners", "0,0,63,0,63,47,0,47", "-o",
                                    "@D@/cc.png", "--ccm", "@D@/cc.json"},
     2, "--chart-corners: the colour fit failed on the patches within the corners (0, 0) (63, 0) (63, 47) (0, 47) (OpenCV: "},
    {"NameWithEscapeBytes", render("colour\x1b[31m.xml"), 2, "scene file not found: @D@/colour\\x1b[31m.xml"},
};

// The promise for one case; `one_line`: an exit 2 case prints its error line alone.
void expect_promise_kept(const HostileCase& c, bool one_line) {
    std::vector<std::string> args;
    for (const std::string& a : c.args) args.push_back(expand(a));
    const CliResult r = run_cli(args, 120, expand(c.shell_prefix), expand(c.stdout_path));
    ASSERT_NE(r.exit_code, 137) << "killed after 120 s: a hang";
    EXPECT_EQ(r.exit_code, c.exit_code) << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
    // stderr reaches a terminal: printable ASCII only, whatever the input held.
    EXPECT_TRUE(std::all_of(r.err.begin(), r.err.end(), [](char ch) { return ch == '\n' || (ch >= 0x20 && ch < 0x7f); }))
        << r.err;
    if (c.exit_code == 2) {
        EXPECT_EQ(r.out, "") << "a failing command prints no partial output";
        // One error line, the last (a command may have reported on its inputs before, e.g. the height map it read).
        const std::string last = r.err.substr(r.err.rfind('\n', r.err.size() - 2) + 1);
        EXPECT_EQ(last.rfind("surfscatter: error: ", 0), 0u) << r.err;
        // No second error line (a library's own, as libpng's used to be), though the one line may quote it.
        std::size_t error_lines = 0;
        for (std::size_t begin = 0; begin < r.err.size();) {
            const std::size_t end = std::min(r.err.find('\n', begin), r.err.size());
            std::string line = r.err.substr(begin, end - begin);
            std::transform(line.begin(), line.end(), line.begin(), [](unsigned char ch) { return std::tolower(ch); });
            if (line.find("error") != std::string::npos) ++error_lines;
            begin = end + 1;
        }
        EXPECT_EQ(error_lines, 1u) << "one error line expected:\n" << r.err;
        EXPECT_NE(r.err.find(expand(c.message)), std::string::npos) << "expected: " << expand(c.message) << "\ngot: " << r.err;
        if (!c.absent.empty()) {
            const fs::path absent = expand(c.absent);
            EXPECT_FALSE(fs::exists(absent)) << absent << " was left behind";
            std::error_code ec;
            for (const auto& entry : fs::directory_iterator(absent.parent_path(), ec))
                for (const std::string& prefix : {absent.filename().string(), std::string(".ss-")})  // output_files.hpp
                    EXPECT_EQ(entry.path().filename().string().rfind(prefix, 0), std::string::npos)
                        << entry.path() << " was left behind";
        }
        if (one_line) {
            EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        }
    } else {
        std::string lower = r.out;
        std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char ch) { return std::tolower(ch); });
        EXPECT_EQ(lower.find("nan"), std::string::npos) << r.out;
        EXPECT_EQ(lower.find("inf"), std::string::npos) << r.out;
    }
}

TEST_P(Hostile, KeepsThePromise) { expect_promise_kept(GetParam(), false); }

class HostileRules : public Hostile {};

TEST_P(HostileRules, KeepsThePromise) { expect_promise_kept(GetParam(), true); }

// Ctrl-C and SIGTERM stop a render that would take hours within a second, and the image of what was rendered is
// written (every pixel a mean of its own samples; the exit status says the job did not finish: 128 + signal).
void expect_interrupt_writes_image(int signal_number) {
    // Own files per signal: ctest runs the two tests at the same time.
    const std::string stem = "interrupt_" + std::to_string(signal_number);
    const fs::path scene_path = dir() / (stem + ".xml"), exr = dir() / (stem + ".exr");
    std::ofstream(scene_path) << scene();
    fs::remove(exr);
    const std::string err = (dir() / (stem + ".err")).string();
    // Not --quiet: the progress bar on stderr tells when the render (and its signal handler) has started.
    const std::vector<std::string> args = {SURFSCATTER_CLI, "render", scene_path.string(), "-D", "size=64", "--spp",
                                           "100000000", "--threads", "2", "-o", exr.string()};
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid = 0;
    ASSERT_EQ(posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ), 0);
    posix_spawn_file_actions_destroy(&actions);
    const auto started = std::chrono::steady_clock::now();
    // stderr is a file: the progress reports the start on a line of its own ("render: started").
    while (surfscatter::test::read_whole_file(err).find("render: started") == std::string::npos) {
        if (std::chrono::steady_clock::now() - started > std::chrono::seconds(60)) {
            kill(pid, SIGKILL);
            waitpid(pid, nullptr, 0);
            FAIL() << "the render did not start within 60 s";
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    ASSERT_EQ(kill(pid, signal_number), 0);
    const auto sent = std::chrono::steady_clock::now();
    int status = 0;
    while (waitpid(pid, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() - sent > std::chrono::seconds(20)) {
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            FAIL() << "the render did not stop within 20 s of the signal";
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
    EXPECT_LT(seconds, 1.0) << "stopping took " << seconds << " s";
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 128 + signal_number);
    const std::string message = surfscatter::test::read_whole_file(err);
    EXPECT_NE(message.find("(interrupted)"), std::string::npos) << message;
    const surfscatter::io::Image image = surfscatter::io::read_image(exr);
    ASSERT_EQ(image.width, 64);
    double sum = 0;
    for (float v : image.pixels) {
        ASSERT_TRUE(std::isfinite(v));
        sum += v;
    }
    EXPECT_GT(sum, 0.0);
}

TEST(HostileInterrupt, CtrlCWritesTheImageWithinASecond) { expect_interrupt_writes_image(SIGINT); }
TEST(HostileInterrupt, SigtermWritesTheImageWithinASecond) { expect_interrupt_writes_image(SIGTERM); }

INSTANTIATE_TEST_SUITE_P(Table, Hostile, testing::ValuesIn(kCases),
                         [](const testing::TestParamInfo<HostileCase>& param) { return param.param.name; });
INSTANTIATE_TEST_SUITE_P(Table, HostileRules, testing::ValuesIn(kRuleCases),
                         [](const testing::TestParamInfo<HostileCase>& param) { return param.param.name; });

}  // namespace
