// surfscatter undistort: removes lens distortion so the photograph matches a pinhole rendering with the same matrix.
#include <cstdio>
#include <string>

#include "command.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/photo/photo_io.hpp"
#include "surfscatter/photo/undistort.hpp"

namespace surfscatter::cli {
namespace {

struct Options {
    std::string photo;
    std::string camera;
    std::string encoding = "srgb";
    std::string output;
};

const Command command("undistort", [](CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* sub = app.add_subcommand(
        "undistort",
        "Removes lens distortion (same size and camera matrix, bilinear resampling). PNG/TIFF outputs are 16-bit "
        "sRGB-encoded, JPEG 8-bit, EXR linear float.");
    sub->add_option("photo", o->photo, "photograph (PNG, JPEG, TIFF, EXR)")->required();
    sub->add_option("--camera", o->camera, "camera file from 'surfscatter calibrate'")->required();
    sub->add_option("--input-encoding", o->encoding, "samples of PNG/JPEG/TIFF inputs: srgb or linear")
        ->capture_default_str();
    sub->add_option("-o,--output", o->output, "undistorted image (.png, .tif, .jpg or .exr)")->required();
    sub->callback([o] {
        const auto encoding = photo::encoding_by_name(o->encoding);
        OutputFiles files;
        files.input(o->photo, "photo");
        files.input(o->camera, "--camera");
        files.output(o->output, "-o");
        const photo::CameraModel camera = photo::read_camera(o->camera);
        const photo::Photo image = photo::read_photo(o->photo, encoding);
        const cv::Mat undistorted = photo::undistort_image(image.rgb, camera);
        files.write_with(o->output, [&](const std::filesystem::path& tmp) { photo::write_photo(tmp, undistorted, encoding); });
        files.commit();
        std::fprintf(stderr, "surfscatter: undistort: %s -> %s\n", printable_path(o->photo).c_str(),
                     printable_path(o->output).c_str());
    });
});

}  // namespace
}  // namespace surfscatter::cli
