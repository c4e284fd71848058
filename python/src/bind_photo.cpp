// Photographs (photo/): reading and writing, boards and lens calibration, camera pose, undistortion, colour
// correction by a ColorChecker and comparison with renderings. Images are numpy arrays (height, width, 3) of linear
// RGB float32, as the photo module holds them (CV_32FC3, R G B); reports are the dicts of the JSON the CLI writes.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/imgproc.hpp>
#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/calibration.hpp"
#include "surfscatter/photo/camera_model.hpp"
#include "surfscatter/photo/chart_correction.hpp"
#include "surfscatter/photo/compare.hpp"
#include "surfscatter/photo/markers.hpp"
#include "surfscatter/photo/photo_io.hpp"
#include "surfscatter/photo/pose_report.hpp"
#include "surfscatter/photo/undistort.hpp"

namespace surfscatter::python {

namespace {

using namespace pybind11::literals;

py::array_t<float> from_mat(const cv::Mat& rgb) {
    const cv::Mat continuous = rgb.isContinuous() ? rgb : rgb.clone();
    return to_float_image(continuous.ptr<float>(), continuous.rows, continuous.cols, 3);
}

bool is_path(py::handle value) {
    return py::isinstance<py::str>(value) || py::isinstance(value, py::module_::import("os").attr("PathLike"));
}

// A photograph given as a path (read with `encoding`) or as a numpy array (height, width, 3) of linear RGB.
photo::Photo photo_value(py::handle value, const char* name, photo::Encoding encoding) {
    if (is_path(value)) {
        const std::string path = path_string(value, name);
        py::gil_scoped_release release;
        return photo::read_photo(path, encoding);
    }
    const RealArray a = real_array(value, name);
    if (a.ndim() != 3 || a.shape(2) != 3)
        fail("{} must be a path or an array (height, width, 3) of linear RGB, got {} dimensions", name, a.ndim());
    photo::Photo p;
    p.rgb = cv::Mat(static_cast<int>(a.shape(0)), static_cast<int>(a.shape(1)), CV_32FC3);
    const double* v = a.data();
    auto* out = p.rgb.ptr<float>();
    for (std::size_t i = 0, n = static_cast<std::size_t>(a.size()); i < n; ++i) out[i] = static_cast<float>(v[i]);
    p.bit_depth = 32;
    return p;
}

cv::Mat photo_input(py::handle value, const char* name, photo::Encoding encoding) {
    return photo_value(value, name, encoding).rgb;
}

// How messages name an input: its path, or `fallback` for an array.
std::string input_name(py::handle value, const std::string& fallback) {
    return is_path(value) ? path_string(value, fallback.c_str()) : fallback;
}

void warn(const std::string& text) {
    if (PyErr_WarnEx(PyExc_UserWarning, text.c_str(), 1) != 0) throw py::error_already_set();  // warnings as errors
}

py::object python_json(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

// (width, height) of whole numbers from a Python pair.
std::pair<int, int> size_pair(py::handle value, const char* name) {
    if (!py::isinstance<py::sequence>(value) || py::isinstance<py::str>(value) || py::len(value) != 2)
        fail("{} must be a pair (x, y) of whole numbers, got {}", name, py::repr(value).cast<std::string>());
    const auto seq = value.cast<py::sequence>();
    std::pair<int, int> out;
    int* both[2] = {&out.first, &out.second};
    for (std::size_t i = 0; i < 2; ++i) {
        if (!py::isinstance<py::int_>(seq[i]) || py::isinstance<py::bool_>(seq[i]))
            fail("{} must be a pair (x, y) of whole numbers, got {}", name, py::repr(value).cast<std::string>());
        int overflow = 0;  // photo::validate checks the range; here only that it is an int
        const long long v = PyLong_AsLongLongAndOverflow(seq[i].ptr(), &overflow);
        if (overflow != 0 || v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
            fail("{} must be a pair (x, y) of whole numbers, got {}", name, py::repr(value).cast<std::string>());
        *both[i] = static_cast<int>(v);
    }
    return out;
}

// The names a Board's parameters have in Python, for the library's messages.
photo::BoardParameterNames python_board_names() {
    return {"squares", "square_length_m", "markers", "marker_length_m", "marker_separation_m"};
}

// A board of `type` with `count` squares (charuco, chessboard) or markers (grid), validated by the library.
photo::BoardSpec make_board(photo::BoardType type, py::handle count, double square_length_m, double marker_length_m,
                            double marker_separation_m, const std::string& dictionary) {
    photo::BoardSpec b;
    b.type = type;
    if (type == photo::BoardType::Grid) std::tie(b.markers_x, b.markers_y) = size_pair(count, "markers");
    else std::tie(b.squares_x, b.squares_y) = size_pair(count, "squares");
    b.square_length = square_length_m;
    b.marker_length = marker_length_m;
    b.marker_separation = marker_separation_m;
    b.dictionary = dictionary;
    photo::validate(b, python_board_names());
    return b;
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
        .def_readonly("calibration_warnings", &photo::CameraModel::calibration_warnings,
                      "why the calibration is weak, one sentence each (empty if it is not, or unknown)")
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

    py::class_<photo::BoardSpec>(m, "Board",
                                 "A calibration or pose board (markers.hpp, docs/PHOTO.md): made by Board.charuco, "
                                 "Board.chessboard or Board.grid; lengths in metres as printed.")
        .def_static(
            "charuco",
            [](py::handle squares, double square_length_m, double marker_length_m, const std::string& dictionary) {
                return make_board(photo::BoardType::Charuco, squares, square_length_m, marker_length_m, 0.0, dictionary);
            },
            py::arg("squares"), py::arg("square_length_m"), py::arg("marker_length_m"), py::arg("dictionary") = "4X4_50",
            "A ChArUco board of squares = (x, y) chessboard squares of square_length_m metres with markers of "
            "marker_length_m metres from `dictionary` (a name such as '4X4_50' or an OpenCV dictionary file), as "
            "--board charuco --squares XxY --square-length --marker-length --dictionary.")
        .def_static(
            "chessboard",
            [](py::handle squares, double square_length_m) {
                return make_board(photo::BoardType::Chessboard, squares, square_length_m, 0.0, 0.0, photo::BoardSpec{}.dictionary);
            },
            py::arg("squares"), py::arg("square_length_m"),
            "A chess board of squares = (x, y) squares (not inner corners) of square_length_m metres, as --board "
            "chessboard (calibration only: a chess board cannot tell its orientation for a pose).")
        .def_static(
            "grid",
            [](py::handle markers, double marker_length_m, double marker_separation_m, const std::string& dictionary) {
                return make_board(photo::BoardType::Grid, markers, 0.0, marker_length_m, marker_separation_m, dictionary);
            },
            py::arg("markers"), py::arg("marker_length_m"), py::arg("marker_separation_m"),
            py::arg("dictionary") = "4X4_50",
            "An ArUco grid board of markers = (x, y) markers of marker_length_m metres, marker_separation_m metres "
            "apart, as --board grid (pose only: its corners are fitted through a calibrated lens).")
        .def_property_readonly("type", [](const photo::BoardSpec& b) { return photo::board_type_name(b.type); },
                               "'charuco', 'chessboard' or 'grid'")
        .def_property_readonly("squares", [](const photo::BoardSpec& b) { return py::make_tuple(b.squares_x, b.squares_y); },
                               "(x, y) squares (charuco, chessboard)")
        .def_property_readonly("markers", [](const photo::BoardSpec& b) { return py::make_tuple(b.markers_x, b.markers_y); },
                               "(x, y) markers (grid)")
        .def_readonly("square_length_m", &photo::BoardSpec::square_length, "square edge in metres (charuco, chessboard)")
        .def_readonly("marker_length_m", &photo::BoardSpec::marker_length, "marker edge in metres (charuco, grid)")
        .def_readonly("marker_separation_m", &photo::BoardSpec::marker_separation, "gap between markers in metres (grid)")
        .def_readonly("dictionary", &photo::BoardSpec::dictionary, "ArUco dictionary name or file (charuco, grid)")
        .def("__repr__", [](const photo::BoardSpec& b) {
            if (b.type == photo::BoardType::Grid)
                return fmt::format("surfscatter.Board.grid(markers=({}, {}), marker_length_m={}, marker_separation_m={}, "
                                   "dictionary='{}')", b.markers_x, b.markers_y, b.marker_length, b.marker_separation,
                                   b.dictionary);
            if (b.type == photo::BoardType::Chessboard)
                return fmt::format("surfscatter.Board.chessboard(squares=({}, {}), square_length_m={})", b.squares_x,
                                   b.squares_y, b.square_length);
            return fmt::format("surfscatter.Board.charuco(squares=({}, {}), square_length_m={}, marker_length_m={}, "
                               "dictionary='{}')", b.squares_x, b.squares_y, b.square_length, b.marker_length,
                               b.dictionary);
        });

    m.def(
        "calibrate",
        [](const py::sequence& images, const photo::BoardSpec& board, bool fit_k3, const std::string& encoding) {
            const auto e = photo::encoding_by_name(encoding);
            std::vector<photo::CalibrationInput> views;
            for (std::size_t i = 0; i < py::len(images); ++i) {
                const std::string name = input_name(images[i], fmt::format("images[{}]", i));
                views.push_back({name, photo_input(images[i], name.c_str(), e)});
            }
            photo::CalibrationResult result;
            {
                py::gil_scoped_release release;
                result = photo::calibrate_camera(views, board, fit_k3);
            }
            for (const auto& name : result.rejected) warn(fmt::format("board not found in '{}' (image not used)", name));
            for (const auto& warning : result.camera.calibration_warnings) warn(warning);
            return py::dict("camera"_a = result.camera, "used"_a = result.used, "rejected"_a = result.rejected,
                            "per_view_rms_px"_a = to_array(result.per_view_rms),
                            "tilt_span_deg"_a = result.tilt_span_deg);
        },
        py::arg("images"), py::arg("board"), py::arg("fit_k3") = false, py::arg("encoding") = "srgb",
        "Lens calibration from several photographs of a ChArUco or chess board (Zhang's method, as `surfscatter "
        "calibrate`): images is a list of paths (PNG/JPEG/TIFF samples read with `encoding`) or linear RGB arrays "
        "(height, width, 3); board a Board.charuco or Board.chessboard; fit_k3 also fits the radial term k3 "
        "(wide-angle lenses). Returns {'camera': Camera (with rms_reprojection_error, intrinsics_std_dev and "
        "calibration_warnings; Camera.write gives the CLI's camera file), 'used' and 'rejected' (the images' paths, "
        "or 'images[i]'), 'per_view_rms_px' (pixels, as 'used'), 'tilt_span_deg' (the largest angle between two views' "
        "board normals)}. Views without the board and a weak calibration are also issued as UserWarnings.");

    m.def(
        "pose",
        [](py::handle image, py::handle camera, std::optional<photo::BoardSpec> board,
           std::optional<double> marker_length_m, const std::string& dictionary, std::optional<int> marker_id,
           bool allow_ambiguous) {
            const photo::CameraModel model = camera_input(camera);
            photo::PoseTarget target;
            if (board) {
                if (marker_length_m || marker_id || dictionary != photo::MarkerPoseOptions{}.dictionary)
                    fail("marker_length_m, dictionary and marker_id are for a single marker: a board carries its own");
                target.board = *board;
            } else {
                if (!marker_length_m) fail("marker_length_m is needed for a single marker (or give board)");
                target.marker.marker_length = *marker_length_m;
                target.marker.dictionary = dictionary;
                target.marker.marker_id = marker_id;
                target.marker.length_name = "marker_length_m";
                target.marker.dictionary_name = "dictionary=";
                target.marker.id_name = "marker_id=";
            }
            const std::string name = input_name(image, "image");
            const photo::Photo photo = photo_value(image, "image", photo::Encoding::Srgb);
            photo::PoseReport report;
            {
                py::gil_scoped_release release;
                report = photo::report_pose(photo, "photo '" + name + "'", model, target);
            }
            if (!allow_ambiguous) photo::require_unambiguous(report, "allow_ambiguous=True");
            if (report.pose.ambiguous)
                warn(fmt::format("the pose is ambiguous (ratio {:.2f}, chi-square {:.3g}): its mirror image, in "
                                 "'alternative', reprojects almost as well",
                                 report.pose.ambiguity_ratio, report.pose.ambiguity_chi2));
            for (const auto& note : report.notes) warn(note);
            py::dict out = python_json(report.json);
            out["notes"] = report.notes;
            return out;
        },
        py::arg("image"), py::arg("camera"), py::arg("board") = py::none(), py::arg("marker_length_m") = py::none(),
        py::arg("dictionary") = "4X4_50", py::arg("marker_id") = py::none(), py::arg("allow_ambiguous") = false,
        "Camera pose in the scene frame (docs/PHOTO.md), as `surfscatter pose`: from a single ArUco marker of "
        "marker_length_m metres and `dictionary` (marker_id picks one when several are visible; the frame's origin "
        "is the marker's centre, +z towards the camera, +y towards its top) or from a whole board (a Board.charuco "
        "or Board.grid; origin at the board's centre). image: a path (sRGB PNG/JPEG/TIFF, EXR, camera RAW) or a "
        "linear RGB array (height, width, 3) of the camera's size; camera: a Camera or a camera file. Returns the "
        "dict of the JSON the CLI writes (camera_position_m, opencv, mitsuba with a ready sensor_xml, uncertainty, "
        "ambiguity, alternative, the marker's or board's detection) without its file names, plus 'notes'. An "
        "ambiguous pose (its mirror image reprojects almost as well) raises surfscatter.Error unless "
        "allow_ambiguous=True, which returns both with a UserWarning; notes are UserWarnings too.");

    m.def(
        "colorcorrect",
        [](py::handle image, std::optional<py::handle> chart_corners_px, bool preserve_white, const std::string& fit,
           py::handle flat_field, const std::string& reference, const std::string& linearize) {
            photo::ChartCorrectionOptions options;
            options.objective = photo::ccm_objective_by_name(fit);
            options.preserve_white = preserve_white;
            options.linearize = linearize;
            options.reference = reference;
            options.chart_corners_option = "chart_corners_px";
            options.linearize_option = "linearize";
            if (chart_corners_px && !chart_corners_px->is_none()) {
                const RealArray c = real_array(*chart_corners_px, "chart_corners_px");
                if (c.ndim() != 2 || c.shape(0) != 4 || c.shape(1) != 2)
                    fail("chart_corners_px must have shape (4, 2): (x, y) of the top-left, top-right, bottom-right "
                         "and bottom-left corners, got {} values", c.size());
                std::array<cv::Point2f, 4> corners;
                for (std::size_t i = 0; i < 4; ++i)
                    corners[i] = cv::Point2f(static_cast<float>(c.data()[2 * i]), static_cast<float>(c.data()[2 * i + 1]));
                options.chart_corners = corners;
            }
            const photo::Photo photo = photo_value(image, "image", photo::Encoding::Linear);
            std::optional<photo::Photo> flat;
            std::string flat_name;
            if (!flat_field.is_none()) {
                flat_name = input_name(flat_field, "flat_field");
                flat = photo_value(flat_field, "flat_field", photo::Encoding::Linear);
            }
            photo::ChartCorrection result;
            {
                py::gil_scoped_release release;
                result = photo::correct_with_chart(photo, flat ? &*flat : nullptr, flat_name, options);
            }
            for (const auto& c : result.clipped)
                warn(c + " is clipped (code at the top of the range): its colour was not measured; expose less");
            py::dict out = python_json(result.json);
            out["image"] = from_mat(result.corrected);
            return out;
        },
        py::arg("image"), py::arg("chart_corners_px") = py::none(), py::arg("preserve_white") = false,
        py::arg("fit") = "ciede2000", py::arg("flat_field") = py::none(),
        py::arg("reference") = photo::kArgyllColorChecker, py::arg("linearize") = "auto",
        "Colour correction by an X-Rite ColorChecker Classic in the photograph, as `surfscatter colorcorrect`: the "
        "chart found by OpenCV mcc, or its patch grid's outer corners given as chart_corners_px (4, 2) in pixels "
        "(dark skin top-left, then clockwise); a per-channel tone curve (linearize 'auto' | 'srgb' | 'linear' | "
        "'gamma' | 'poly') and a 3x3 matrix fitted to the reference (fit 'ciede2000' | 'least-squares'; "
        "preserve_white maps the white patch exactly), optionally after evening the chart's light by a flat-field "
        "photograph of a grey card. image and flat_field: paths (PNG/JPEG/TIFF code values are linearised by the "
        "fitted curve) or arrays (height, width, 3) taken as linear light, like an EXR. Returns the dict of the JSON "
        "`--ccm` writes (ccm, linearization, ciede2000_before/after, patches, clipped_patches, ...) plus 'image', "
        "the corrected photograph as linear sRGB float32. Clipped patches are also UserWarnings.");

    m.def(
        "compare",
        [](py::handle image, const py::sequence& renders, std::optional<std::vector<std::string>> labels, py::handle mask,
           const std::string& encoding) {
            if (labels && labels->size() != py::len(renders))
                fail("labels has {} entries for {} renderings", labels->size(), py::len(renders));
            const auto e = photo::encoding_by_name(encoding);
            const cv::Mat photo = photo_input(image, "image", e);
            cv::Mat mask_mat;
            if (is_path(mask)) {
                mask_mat = photo::read_mask(path_string(mask, "mask"), photo.size());
            } else if (!mask.is_none()) {
                py::object values = py::module_::import("numpy").attr("asarray")(mask);
                if (values.attr("dtype").attr("kind").cast<std::string>() == "b") values = values.attr("astype")("uint8");
                const RealArray a = real_array(values, "mask");
                if (a.ndim() != 2) fail("mask must be a path or an array (height, width), got {} dimensions", a.ndim());
                mask_mat = cv::Mat(static_cast<int>(a.shape(0)), static_cast<int>(a.shape(1)), CV_8UC1);
                for (py::ssize_t i = 0; i < a.size(); ++i) mask_mat.data[i] = a.data()[i] != 0 ? 255 : 0;
            }
            std::vector<cv::Mat> rendered;
            std::vector<photo::ComparisonMetrics> metrics;
            py::list rows;
            for (std::size_t i = 0; i < py::len(renders); ++i) {
                const std::string name = input_name(renders[i], fmt::format("renders[{}]", i));
                rendered.push_back(photo_input(renders[i], name.c_str(), e));
                const std::string label = labels ? (*labels)[i]
                                          : is_path(renders[i]) ? std::filesystem::path(name).stem().string()
                                                                : fmt::format("render {}", i + 1);
                try {
                    metrics.push_back(photo::compare_to_photo(photo, rendered.back(), mask_mat, label));
                } catch (const Error& error) {
                    fail("rendering '{}': {}", name, error.what());
                }
                const auto& r = metrics.back();
                rows.append(py::dict("label"_a = r.label, "exposure_scale"_a = r.exposure_scale, "rmse"_a = r.rmse,
                                     "psnr_db"_a = r.psnr_db, "ssim"_a = r.ssim, "mean_ciede2000"_a = r.mean_ciede2000));
            }
            cv::Mat sheet;
            {
                py::gil_scoped_release release;
                cv::cvtColor(photo::comparison_sheet(photo, rendered, mask_mat, metrics), sheet, cv::COLOR_BGR2RGB);
            }
            py::array_t<std::uint8_t> sheet_array({static_cast<py::ssize_t>(sheet.rows),
                                                   static_cast<py::ssize_t>(sheet.cols), py::ssize_t{3}});
            for (int y = 0; y < sheet.rows; ++y)
                std::memcpy(sheet_array.mutable_data(y), sheet.ptr(y), static_cast<std::size_t>(sheet.cols) * 3);
            return py::dict("renders"_a = rows, "sheet"_a = sheet_array);
        },
        py::arg("image"), py::arg("renders"), py::arg("labels") = py::none(), py::arg("mask") = py::none(),
        py::arg("encoding") = "srgb",
        "A photograph against renderings, as `surfscatter compare`: each rendering scaled by the least-squares "
        "exposure factor over the mask, then RMSE, PSNR (dB), SSIM and mean CIEDE2000 inside the mask (compare.hpp). "
        "image and renders: paths (PNG/JPEG/TIFF samples read with `encoding`) or linear RGB arrays (height, width, 3) "
        "of one size; labels: one per rendering (default: the file's stem, or 'render i'); mask: a path of an 8-bit "
        "image or an array (height, width), non-zero = compared (default: everything). Returns {'renders': [{'label', "
        "'exposure_scale', 'rmse', 'psnr_db', 'ssim', 'mean_ciede2000'}, ...], 'sheet': the labelled comparison "
        "sheet as uint8 sRGB (rows, columns, 3)}.");
}

}  // namespace surfscatter::python
