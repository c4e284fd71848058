// Photographs (photo/): reading and writing, camera files, undistortion; images are numpy arrays (height, width, 3)
// of linear RGB float32, as the photo module holds them (CV_32FC3, R G B).
#include <cstring>
#include <optional>

#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/camera_model.hpp"
#include "surfscatter/photo/photo_io.hpp"
#include "surfscatter/photo/undistort.hpp"

namespace surfscatter::python {

namespace {

using namespace pybind11::literals;

py::array_t<float> from_mat(const cv::Mat& rgb) {
    const cv::Mat continuous = rgb.isContinuous() ? rgb : rgb.clone();
    return to_float_image(continuous.ptr<float>(), continuous.rows, continuous.cols, 3);
}

// A photograph given as a path (read with `encoding`) or as a numpy array (height, width, 3) of linear RGB.
cv::Mat photo_input(py::handle value, const char* name, photo::Encoding encoding) {
    if (py::isinstance<py::str>(value) || py::isinstance(value, py::module_::import("os").attr("PathLike")))
        return photo::read_photo(path_string(value, name), encoding).rgb;
    const RealArray a = real_array(value, name);
    if (a.ndim() != 3 || a.shape(2) != 3)
        fail("{} must be a path or an array (height, width, 3) of linear RGB, got {} dimensions", name, a.ndim());
    const int rows = static_cast<int>(a.shape(0)), cols = static_cast<int>(a.shape(1));
    cv::Mat rgb(rows, cols, CV_32FC3);
    const double* v = a.data();
    auto* out = rgb.ptr<float>();
    for (std::size_t i = 0, n = static_cast<std::size_t>(a.size()); i < n; ++i) out[i] = static_cast<float>(v[i]);
    return rgb;
}

photo::CameraModel camera_input(py::handle value) {
    if (py::isinstance<photo::CameraModel>(value)) return value.cast<photo::CameraModel>();
    return photo::read_camera(path_string(value, "camera (a Camera or the path of a camera file)"));
}

RealArray matrix_array(const cv::Matx33d& m) {
    RealArray out({3, 3});
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) out.mutable_at(r, c) = m(r, c);
    return out;
}

}  // namespace

void bind_photo(py::module_& m) {
    m.def(
        "read_photo",
        [](py::handle path, const std::string& encoding) {
            const auto e = photo::encoding_by_name(encoding);
            const std::string file = path_string(path, "path");
            photo::Photo p;
            {
                py::gil_scoped_release release;
                p = photo::read_photo(file, e);
            }
            return from_mat(p.rgb);
        },
        py::arg("path"), py::arg("encoding") = "srgb",
        "A photograph or rendering as linear RGB, float32 (height, width, 3), 1 = the file's full scale: JPEG, "
        "8/16-bit PNG/TIFF (encoding 'srgb' decodes the sRGB curve, 'linear' takes samples as they are), OpenEXR "
        "(linear), camera RAW through LibRaw (linear sRGB). docs/PHOTO.md.");
    m.def(
        "write_photo",
        [](py::handle path, py::handle image, const std::string& encoding) {
            const auto e = photo::encoding_by_name(encoding);
            photo::write_photo(path_string(path, "path"), photo_input(image, "image", e), e);
        },
        py::arg("path"), py::arg("image"), py::arg("encoding") = "srgb",
        "Writes linear RGB (height, width, 3) by extension: .png/.tif 16-bit and .jpg 8-bit, sRGB-encoded unless "
        "encoding is 'linear' (values outside [0, 1] clipped); .exr 32-bit float, linear.");

    py::class_<photo::CameraModel>(m, "Camera",
                                   "A calibrated pinhole camera with OpenCV's distortion model (k1 k2 p1 p2 [k3]), "
                                   "pixel centres at integer coordinates (camera_model.hpp).")
        .def_property_readonly("image_size", [](const photo::CameraModel& c) {
            return py::make_tuple(c.image_size.width, c.image_size.height);
        }, "(width, height) in pixels")
        .def_property_readonly("matrix", [](const photo::CameraModel& c) { return matrix_array(c.matrix); },
                               "[[fx, 0, cx], [0, fy, cy], [0, 0, 1]] in pixels")
        .def_property_readonly("distortion", [](const photo::CameraModel& c) { return to_array(c.distortion); },
                               "k1 k2 p1 p2 k3 (OpenCV order)")
        .def_property_readonly("fx", &photo::CameraModel::fx, "focal length along x (pixels)")
        .def_property_readonly("fy", &photo::CameraModel::fy, "focal length along y (pixels)")
        .def_property_readonly("cx", &photo::CameraModel::cx, "principal point x (pixels, centres at integers)")
        .def_property_readonly("cy", &photo::CameraModel::cy, "principal point y (pixels)")
        .def_readonly("rms_reprojection_error", &photo::CameraModel::rms_reprojection_error, "pixels (0 if unknown)")
        .def_readonly("views", &photo::CameraModel::views, "images the calibration used")
        .def_property_readonly(
            "intrinsics_std_dev", [](const photo::CameraModel& c) { return to_array(c.intrinsics_std_dev); },
            "one standard deviation of fx, fy, cx, cy and each distortion coefficient (empty if unknown)")
        .def(
            "write", [](const photo::CameraModel& c, py::handle path) { photo::write_camera(path_string(path, "path"), c); },
            py::arg("path"), "Writes the OpenCV YAML camera file `surfscatter calibrate` writes.")
        .def("__repr__", [](const photo::CameraModel& c) {
            return fmt::format("<surfscatter.Camera {}x{} fx={:.6g} fy={:.6g} cx={:.6g} cy={:.6g}>", c.image_size.width,
                               c.image_size.height, c.fx(), c.fy(), c.cx(), c.cy());
        });
    m.def(
        "read_camera", [](py::handle path) { return photo::read_camera(path_string(path, "path")); }, py::arg("path"),
        "Reads a camera file written by `surfscatter calibrate` (or Camera.write).");

    m.def(
        "undistort",
        [](py::handle image, py::handle camera, const std::string& encoding) {
            const photo::CameraModel model = camera_input(camera);
            const cv::Mat rgb = photo_input(image, "image", photo::encoding_by_name(encoding));
            cv::Mat out;
            {
                py::gil_scoped_release release;
                out = photo::undistort_image(rgb, model);
            }
            return from_mat(out);
        },
        py::arg("image"), py::arg("camera"), py::arg("encoding") = "srgb",
        "Removes lens distortion (same size and camera matrix, bilinear): image is a path (PNG/JPEG/TIFF samples "
        "read with `encoding`) or a linear RGB array (height, width, 3); camera a Camera or a camera file. Returns "
        "linear RGB float32, as `surfscatter undistort`.");
}

}  // namespace surfscatter::python
