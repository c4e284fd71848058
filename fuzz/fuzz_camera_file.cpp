// Fuzz target: the camera-file reader (photo/camera_model.hpp, YAML through cv::FileStorage); a camera that loads
// has finite, positive focal lengths and finite distortion.
#include "fuzz_common.hpp"
#include "surfscatter/photo/camera_model.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace surfscatter;
    const auto path = fuzz::write_input("camera.yml", fuzz::as_text(data, size));
    fuzz::expect_clean([&] {
        const photo::CameraModel camera = photo::read_camera(path);
        FUZZ_CHECK(std::isfinite(camera.fx()) && camera.fx() > 0 && std::isfinite(camera.fy()) && camera.fy() > 0);
        FUZZ_CHECK(std::isfinite(camera.cx()) && std::isfinite(camera.cy()));
        for (double d : camera.distortion) FUZZ_CHECK(std::isfinite(d));
    });
    return 0;
}
