"""Photographs from Python: reading and writing, camera files, undistortion against `surfscatter undistort`."""

import numpy as np
import pytest

import surfscatter as ss
from conftest import run_cli, shared

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
        (lambda cam: ss.write_photo("/tmp/x.exr", np.full((4, 4, 3), np.nan)), "image must be finite"),
        (lambda cam: ss.read_camera("/nonexistent/camera.yml"), "does not exist"),
        (lambda cam: ss.undistort(np.zeros((10, 10, 3)), cam), "640x480"),
        (lambda cam: ss.undistort(np.zeros((480, 640, 3)), 5), "camera"),
    ],
)
def test_bad_input_raises_error_naming_it(call, message, camera_file):
    with pytest.raises(ss.Error, match=message):
        call(camera_file)
