"""Photographs from Python: reading and writing, camera files, undistortion, calibration, pose, colour correction
and comparison, each against the CLI on the same files and against what the synthetic photographs were made with."""

import json
import warnings

import numpy as np
import pytest

import surfscatter as ss
import synthetic
from conftest import run_cli, shared

ARGYLL_CHART = "/usr/share/color/argyll/ref/ColorChecker.cie"

# OpenCV's ArUco tutorial camera (tutorial_camera_params.yml) with the size of its 640 x 480 photographs.
CAMERA_YML = """%YAML:1.0
---
image_width: 640
image_height: 480
camera_matrix: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 628.158, 0., 324.099, 0., 628.156, 260.908, 0., 0., 1. ]
distortion_coefficients: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data: [ 0.0995485, -0.206384, 0.00754589, 0.00336531, 0. ]
"""


@pytest.fixture
def camera_file(tmp_path):
    path = tmp_path / "camera.yml"
    path.write_text(CAMERA_YML)
    return path


def test_read_photo_decodes_srgb_to_linear_and_round_trips():
    jpg = shared("realdata", "photos", "singlemarkersoriginal.jpg")
    linear = ss.read_photo(jpg)
    raw = ss.read_photo(jpg, encoding="linear")
    assert linear.dtype == np.float32 and linear.shape == (480, 640, 3)
    # sRGB decoding, written out here: ((c + 0.055) / 1.055)^2.4 above 0.04045, c / 12.92 below.
    c = raw.astype(np.float64)
    decoded = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    np.testing.assert_allclose(linear, decoded, rtol=1e-5, atol=1e-7)


def test_write_photo_round_trips(tmp_path):
    image = np.random.default_rng(4).random((12, 20, 3)).astype(np.float32)
    ss.write_photo(tmp_path / "a.exr", image)
    np.testing.assert_array_equal(ss.read_photo(tmp_path / "a.exr"), image)
    ss.write_photo(tmp_path / "a.png", image)  # 16-bit sRGB-encoded
    np.testing.assert_allclose(ss.read_photo(tmp_path / "a.png"), image, atol=2e-4)


def test_camera_file_and_undistort_equal_the_cli(tmp_path, camera_file):
    jpg = shared("realdata", "photos", "singlemarkersoriginal.jpg")
    camera = ss.read_camera(camera_file)
    assert camera.image_size == (640, 480) and camera.fx == 628.158
    np.testing.assert_array_equal(camera.matrix, [[628.158, 0, 324.099], [0, 628.156, 260.908], [0, 0, 1]])
    np.testing.assert_array_equal(camera.distortion, [0.0995485, -0.206384, 0.00754589, 0.00336531, 0.0])
    run_cli("undistort", jpg, "--camera", camera_file, "-o", tmp_path / "cli.exr")
    cli = ss.read_photo(tmp_path / "cli.exr")
    np.testing.assert_array_equal(ss.undistort(jpg, camera_file), cli)
    np.testing.assert_array_equal(ss.undistort(ss.read_photo(jpg), camera), cli)
    camera.write(tmp_path / "again.yml")
    np.testing.assert_array_equal(ss.read_camera(tmp_path / "again.yml").matrix, camera.matrix)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda cam: ss.read_photo("/nonexistent/photo.png"), "/nonexistent/photo.png"),
        (lambda cam: ss.read_photo(shared("realdata", "photos", "gboriginal.jpg"), encoding="gamma"),
         "unknown sample encoding 'gamma'"),
        (lambda cam: ss.write_photo("/tmp/x.exr", np.zeros((4, 4))), r"image must be a path or an array \(height, width, 3\)"),
        (lambda cam: ss.write_photo("/tmp/x.exr", np.full((4, 4, 3), np.nan)), "image must be a finite number"),
        (lambda cam: ss.read_camera("/nonexistent/camera.yml"), "does not exist"),
        (lambda cam: ss.undistort(np.zeros((10, 10, 3)), cam), "640x480"),
        (lambda cam: ss.undistort(np.zeros((480, 640, 3)), 5), "camera"),
    ],
)
def test_bad_input_raises_error_naming_it(call, message, camera_file):
    with pytest.raises(ss.Error, match=message):
        call(camera_file)


# ---- calibration (synthetic chess board photographs, made in synthetic.py)

@pytest.fixture(scope="module")
def board_views(tmp_path_factory):
    """Seven 16-bit PNG photographs of a 9 x 6 chess board (25 mm squares) through the synthetic camera."""
    folder = tmp_path_factory.mktemp("board")
    rays = synthetic.pixel_rays()
    paths = []
    for k, eye in enumerate(synthetic.calibration_views()):
        path = folder / f"view{k}.png"
        ss.write_photo(path, synthetic.chessboard_photo(rays, eye, np.zeros(3)))
        paths.append(path)
    return paths


def test_calibrate_recovers_the_camera_and_writes_the_clis_camera_file(board_views, tmp_path):
    board = ss.Board.chessboard((9, 6), square_length_m=0.025)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a good calibration: no rejected view, no weak-calibration warning
        result = ss.calibrate(board_views, board)
    camera = result["camera"]
    assert result["used"] == [str(p) for p in board_views] and result["rejected"] == []
    assert result["per_view_rms_px"].shape == (7,) and np.all(result["per_view_rms_px"] < 0.3)
    assert result["tilt_span_deg"] == pytest.approx(60.0, abs=0.5)  # views tilted 30 degrees in opposite directions
    assert camera.image_size == synthetic.IMAGE_SIZE and camera.views == 7 and camera.calibration_warnings == []
    # The truth lies within three of the calibration's own standard deviations.
    sd = camera.intrinsics_std_dev
    for value, truth, s in zip((camera.fx, camera.fy, camera.cx, camera.cy),
                               (synthetic.FX, synthetic.FY, synthetic.CX, synthetic.CY), sd[:4]):
        assert abs(value - truth) < 3 * s, (value, truth, s)
    # The CLI on the same files writes the same camera file, byte for byte.
    run_cli("calibrate", *board_views, "--board", "chessboard", "--squares", "9x6", "--square-length", "0.025",
            "-o", tmp_path / "cli.yml")
    camera.write(tmp_path / "python.yml")
    assert (tmp_path / "python.yml").read_text() == (tmp_path / "cli.yml").read_text()
    # Arrays in: the same views as linear RGB give the same calibration.
    from_arrays = ss.calibrate([ss.read_photo(p) for p in board_views], board)
    np.testing.assert_array_equal(from_arrays["camera"].matrix, camera.matrix)
    assert from_arrays["used"] == [f"images[{k}]" for k in range(7)]


def test_calibrate_warns_about_views_without_the_board(board_views, tmp_path):
    blank = tmp_path / "blank.png"
    ss.write_photo(blank, np.full((480, 640, 3), 0.5, np.float32))
    with pytest.warns(UserWarning, match=f"board not found in '{blank}' \\(image not used\\)"):
        result = ss.calibrate([*board_views[:4], blank], ss.Board.chessboard((9, 6), 0.025))
    assert result["rejected"] == [str(blank)] and len(result["used"]) == 4


# ---- pose (the real photographs of OpenCV's ArUco tutorial)

@pytest.fixture
def grid_board():
    # The tutorial's 5 x 7 grid of 40 mm markers of its own dictionary; the 8 mm gap fits the photo.
    return ss.Board.grid((5, 7), marker_length_m=0.04, marker_separation_m=0.008,
                         dictionary=str(shared("realdata", "photos", "tutorial_dict.yml")))


def cli_pose(tmp_path, *args):
    run_cli("pose", *args, "-o", tmp_path / "pose.json")
    result = json.loads((tmp_path / "pose.json").read_text())
    del result["photo"], result["camera_file"]
    return result


def test_board_pose_equals_the_clis_json(tmp_path, camera_file, grid_board):
    photo = shared("realdata", "photos", "gboriginal.jpg")
    result = ss.pose(photo, camera_file, board=grid_board)
    assert result.pop("notes") == []
    assert result == cli_pose(tmp_path, photo, "--camera", camera_file, "--board", "grid", "--markers", "5x7",
                              "--marker-length", "0.04", "--marker-separation", "0.008", "--dictionary",
                              grid_board.dictionary)
    assert result["board"]["markers_detected"] == 35 and result["board"]["corners_used"] == 140
    # The camera-to-world transform is a rigid motion whose translation is the camera's position.
    to_world = np.array(result["opencv"]["camera_to_world"])
    np.testing.assert_allclose(to_world[:3, :3] @ to_world[:3, :3].T, np.eye(3), atol=1e-12)
    np.testing.assert_allclose(to_world[:3, 3], result["camera_position_m"], atol=1e-12)
    # A linear RGB array of the photograph gives the same pose (no EXIF focal length: none in this JPEG).
    from_array = ss.pose(ss.read_photo(photo), ss.read_camera(camera_file), board=grid_board)
    assert from_array["camera_position_m"] == result["camera_position_m"]


def test_single_marker_pose_equals_the_clis_and_agrees_with_the_board(tmp_path, camera_file, grid_board):
    photo = shared("realdata", "photos", "gboriginal.jpg")
    marker = ss.pose(photo, camera_file, marker_length_m=0.04, dictionary=grid_board.dictionary, marker_id=17)
    marker.pop("notes")
    assert marker == cli_pose(tmp_path, photo, "--camera", camera_file, "--marker-length", "0.04", "--dictionary",
                              grid_board.dictionary, "--marker-id", "17")
    assert marker["marker"]["id"] == 17 and not marker["ambiguity"]["ambiguous"]
    # Marker 17 sits in row 3, column 2 (0-based, row by row) of the 5 x 7 grid of 40 mm markers 8 mm apart: its centre
    # is (2 * 48 + 20 - 116, 3 * 48 + 20 - 164) mm = (0, 0) from the board's centre, so both frames coincide and
    # both poses put the camera at one place (test_cli_photo.cpp holds the CLI to the same 5 cm).
    board = ss.pose(photo, camera_file, board=grid_board)
    apart = np.linalg.norm(np.subtract(marker["camera_position_m"], board["camera_position_m"]))
    assert apart < 0.05


def test_an_ambiguous_pose_is_refused_unless_allowed(camera_file, grid_board):
    photo = shared("realdata", "photos", "gboriginal.jpg")
    args = dict(marker_length_m=0.04, dictionary=grid_board.dictionary, marker_id=30)
    with pytest.raises(ss.Error, match=r"the pose of marker 30 is ambiguous: .* or pass allow_ambiguous=True to get "
                                       r"both poses$"):
        ss.pose(photo, camera_file, **args)
    with pytest.warns(UserWarning, match="the pose is ambiguous"):
        result = ss.pose(photo, camera_file, allow_ambiguous=True, **args)
    assert result["ambiguity"]["ambiguous"] and "mitsuba" in result["alternative"]
    assert result["ambiguity"]["mirror_angle_deg"] > 10


# ---- colour correction (a synthetic ColorChecker under a colour cast, made in synthetic.py)

@pytest.fixture(scope="module")
def cast_chart(tmp_path_factory):
    reference = synthetic.reference_linear_srgb(ARGYLL_CHART)
    image, corners, centres = synthetic.chart_photo(reference @ synthetic.CAST.T)
    path = tmp_path_factory.mktemp("chart") / "chart.png"
    ss.write_photo(path, image)
    return path, reference, corners, centres


def test_colorcorrect_removes_the_cast_and_equals_the_cli(cast_chart, tmp_path):
    path, reference, corners, centres = cast_chart
    result = ss.colorcorrect(path, chart_corners_px=corners)
    corrected = result.pop("image")
    run_cli("colorcorrect", path, "--chart-corners", ",".join(repr(v) for v in corners.ravel()), "-o",
            tmp_path / "cli.exr", "--ccm", tmp_path / "cli.json")
    cli = json.loads((tmp_path / "cli.json").read_text())
    del cli["photo"]
    assert result == cli
    np.testing.assert_array_equal(corrected, ss.read_photo(tmp_path / "cli.exr"))
    # The reference the library converts from CIELAB D50 is the one written out in synthetic.py.
    np.testing.assert_allclose(result["patches_reference_linear_srgb"], reference, atol=5e-4)
    # The corrected photograph's patch centres are the reference: the cast is gone.
    patches = corrected[np.round(centres[:, 1]).astype(int), np.round(centres[:, 0]).astype(int)]
    np.testing.assert_allclose(patches, np.clip(reference, 0, 1), atol=0.03)  # the fit minimises CIEDE2000, not RGB
    assert result["ciede2000_before"]["mean"] > 5 and result["ciede2000_after"]["mean"] < 0.5
    assert result["linearization"]["family"] == "srgb"  # a 16-bit sRGB-encoded PNG


def test_colorcorrect_finds_the_chart(cast_chart):
    path, _, corners, _ = cast_chart
    result = ss.colorcorrect(path, linearize="srgb")
    assert result["chart_detection"] == "OpenCV mcc"
    np.testing.assert_allclose(result["chart_corners_px"], corners, atol=8)  # mcc's corners, within a gap
    assert result["ciede2000_after"]["mean"] < 1


# ---- comparison

def test_compare_matches_the_definitions_and_the_cli(tmp_path):
    rng = np.random.default_rng(7)
    photo = rng.uniform(0.05, 0.9, (60, 80, 3)).astype(np.float32)
    close = (0.5 * photo * rng.uniform(0.97, 1.03, photo.shape)).astype(np.float32)  # half the exposure
    far = rng.uniform(0.05, 0.9, photo.shape).astype(np.float32)
    mask = np.zeros((60, 80), bool)
    mask[10:50, 5:70] = True
    result = ss.compare(photo, [close, far], labels=["close", "far"], mask=mask)
    for row, render in zip(result["renders"], (close, far)):
        p, r = photo[mask].astype(np.float64), render[mask].astype(np.float64)
        k = (p * r).sum() / (r * r).sum()
        mse = ((p - k * r) ** 2).mean()
        assert row["exposure_scale"] == pytest.approx(k, rel=1e-6)
        assert row["rmse"] == pytest.approx(np.sqrt(mse), rel=1e-5)
        assert row["psnr_db"] == pytest.approx(10 * np.log10(p.max() ** 2 / mse), rel=1e-5)
    close_row, far_row = result["renders"]
    assert close_row["exposure_scale"] == pytest.approx(2.0, rel=0.01)
    assert close_row["ssim"] > far_row["ssim"] and close_row["mean_ciede2000"] < far_row["mean_ciede2000"]
    assert result["sheet"].dtype == np.uint8 and result["sheet"].ndim == 3
    # The CLI on the same images (EXR) and mask (PNG) gives the same figures.
    for name, image in (("photo", photo), ("close", close), ("far", far)):
        ss.write_photo(tmp_path / f"{name}.exr", image)
    ss.write_photo(tmp_path / "mask.png", np.repeat(mask[..., None], 3, axis=2).astype(np.float32))
    run_cli("compare", tmp_path / "photo.exr", tmp_path / "close.exr", tmp_path / "far.exr", "--mask",
            tmp_path / "mask.png", "-o", tmp_path / "sheet.png")
    cli = json.loads((tmp_path / "sheet.json").read_text())["renders"]
    from_files = ss.compare(tmp_path / "photo.exr", [tmp_path / "close.exr", tmp_path / "far.exr"],
                            mask=tmp_path / "mask.png")
    for row, cli_row in zip(from_files["renders"], cli):
        assert row == {key: cli_row[key] for key in row}
    cli_sheet = ss.read_photo(tmp_path / "sheet.png", encoding="linear") * 255  # 8-bit codes
    np.testing.assert_allclose(from_files["sheet"], cli_sheet, atol=1e-3)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda cam: ss.Board.chessboard((2, 6), 0.025), "squares must be between 3 and 200 per side, got 2"),
        (lambda cam: ss.Board.charuco((10, 7), 0.03, 0.04), "marker_length_m 0.04 must be smaller than square_length_m 0.03"),
        (lambda cam: ss.Board.grid((5, 7), 0.04, -1), r"marker_separation_m must be between 1e-06 and 1000 metres, got -1"),
        (lambda cam: ss.Board.grid((5, 7), 0.04, 0.01, dictionary="5X5_9"), "unknown ArUco dictionary '5X5_9'"),
        (lambda cam: ss.Board.chessboard((9, 2**40), 0.025), r"squares must be a pair \(x, y\) of whole numbers"),
        (lambda cam: ss.Board.chessboard("9x6", 0.025), r"squares must be a pair \(x, y\) of whole numbers"),
        (lambda cam: ss.calibrate([], ss.Board.chessboard((9, 6), 0.025)), "at least 3"),
        (lambda cam: ss.pose(np.zeros((480, 640, 3)), 5), "camera"),
        (lambda cam: ss.pose(np.zeros((480, 640, 3)), cam), "marker_length_m is needed"),
        (lambda cam: ss.pose(np.zeros((480, 640, 3)), cam, marker_length_m=-0.04),
         "marker_length_m must be positive, got -0.04"),
        (lambda cam: ss.pose(np.zeros((480, 640, 3)), cam, marker_length_m=0.04),
         "no ArUco marker of dictionary 4X4_50 found in the image"),
        (lambda cam: ss.pose(np.zeros((48, 64, 3)), cam, marker_length_m=0.04), "640x480"),
        (lambda cam: ss.pose(np.zeros((480, 640, 3)), cam, board=ss.Board.grid((5, 7), 0.04, 0.01),
                         marker_id=3), "are for a single marker"),
        (lambda cam: ss.colorcorrect(np.zeros((48, 64, 3)), chart_corners_px=[[0, 0], [10, 0], [10, 10]]),
         r"chart_corners_px must have shape \(4, 2\)"),
        (lambda cam: ss.colorcorrect(np.zeros((48, 64, 3)), chart_corners_px=[[0, 0], [70, 0], [10, 10], [0, 10]]),
         r"chart_corners_px: corner 2 \(70, 0\) lies outside the 64x48 image"),
        (lambda cam: ss.colorcorrect(np.zeros((48, 64, 3)), linearize="log"), "log"),
        (lambda cam: ss.colorcorrect(np.zeros((48, 64, 3)), fit="l2"), "l2"),
        (lambda cam: ss.compare(np.zeros((8, 8, 3)), [np.zeros((8, 9, 3))]), r"rendering 'renders\[0\]': "),
        (lambda cam: ss.compare(np.zeros((8, 8, 3)), [np.ones((8, 8, 3))], labels=["a", "b"]),
         "labels has 2 entries for 1 renderings"),
        (lambda cam: ss.compare(np.zeros((8, 8, 3)), [np.ones((8, 8, 3))], mask=np.ones((8, 8, 3))),
         r"mask must be a path or an array \(height, width\)"),
    ],
)
def test_bad_photo_pipeline_input_raises_error_naming_it(call, message, camera_file):
    with pytest.raises(ss.Error, match=message):
        call(camera_file)


def test_pose_names_the_dictionary_that_fits_and_takes_the_size_from_the_photo():
    """OpenCV's own camera file holds camera_matrix and distortion_coefficients only: the photo gives the size. With
    the default dictionary 4X4_50 the 6X6_250 markers of the photo give a false, ambiguous marker; the message says
    which dictionary fits, in Python's terms."""
    jpg = shared("realdata", "photos", "singlemarkersoriginal.jpg")
    camera = shared("realdata", "photos", "tutorial_camera_params.yml")
    assert ss.read_camera(camera).image_size == (0, 0)
    with pytest.raises(ss.Error, match=r"markers of dictionary 6X6_250 \(ids 23, 40, 62, 98, 124, 203\), 1 of 4X4_50: "
                                       r"pass dictionary=6X6_250"):
        ss.pose(jpg, camera, marker_length_m=0.05)
    with pytest.raises(ss.Error, match="several markers found .*; choose one with marker_id="):
        ss.pose(jpg, camera, marker_length_m=0.05, dictionary="6X6_250")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the tutorial camera's notes, if any
        pose = ss.pose(jpg, camera, marker_length_m=0.05, dictionary="6X6_250", marker_id=23, allow_ambiguous=True)
    assert pose["image_size"] == [640, 480] and pose["marker"]["id"] == 23
