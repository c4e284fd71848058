"""The same bad input given to the CLI and to Python gives the same one-line message.

Each case runs the `surfscatter` binary, takes the line it prints after 'surfscatter: error: ', and compares it with
the message of the surfscatter.Error the Python call raises, after renaming the options the line names to the
Python spelling of the same argument ('--theta-i' -> 'theta_i_deg'): the words are the library's in both.
"""

import subprocess

import numpy as np
import pytest

import surfscatter as ss
import synthetic
from conftest import CLI, shared
from test_photo import CAMERA_YML
from test_render import SCENE, SMALL

DEFINES = sum((["-D", f"{k}={v}"] for k, v in SMALL.items()), [])

KC = ["--psd", "kc", "--sigma", "0.1", "--corr-length", "1", "--gamma", "3"]
KC_PY = dict(psd="kc", sigma=0.1, corr_length=1, gamma=3)
ALBEDO = ["brdf", "albedo", "--wavelength", "550", "--theta-i", "10"]
GGX = ["--model", "ggx_stats", "--alpha-from", "none", "--alpha", "0.3", "--material", "perfect"]
GGX_PY = dict(model="ggx_stats", alpha_from="none", alpha=0.3)


def cli_error(args):
    """The message of the CLI's one error line; fails unless the CLI exits with status 2 and prints exactly one."""
    done = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)
    assert done.returncode == 2, f"surfscatter {' '.join(map(str, args))}: exit {done.returncode}: {done.stderr}"
    errors = [line for line in done.stderr.splitlines() if line.startswith("surfscatter: error: ")]
    assert len(errors) == 1, done.stderr
    return errors[0][len("surfscatter: error: "):]


def python_error(call):
    with pytest.raises(ss.Error) as raised:
        call()
    return str(raised.value)


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """A camera file, a blank photograph of its size, a synthetic chart and a 32 x 32 image."""
    folder = tmp_path_factory.mktemp("errors")
    paths = {"camera": folder / "camera.yml", "blank": folder / "blank.png", "small": folder / "small.png",
             "chart": folder / "chart.png", "out": folder / "out"}
    paths["camera"].write_text(CAMERA_YML)
    ss.write_photo(paths["blank"], np.full((480, 640, 3), 0.5, np.float32))
    ss.write_photo(paths["small"], np.full((32, 32, 3), 0.5, np.float32))
    reference = synthetic.reference_linear_srgb("/usr/share/color/argyll/ref/ColorChecker.cie")
    ss.write_photo(paths["chart"], synthetic.chart_photo(reference)[0])
    return paths


def cases(f):
    """(id, CLI arguments, Python call, {CLI option: Python name}) for the fixture's files f."""
    dictionary = str(shared("realdata", "photos", "tutorial_dict.yml"))
    grid = shared("realdata", "photos", "gboriginal.jpg")
    out = f["out"]
    return [
        ("sigma", ["brdf", "albedo", "--psd", "kc", "--sigma", "-1", "--corr-length", "1", "--gamma", "3",
                   "--material", "perfect", "--wavelength", "550", "--theta-i", "10"],
         lambda: ss.bsdf(psd="kc", sigma=-1, corr_length=1, gamma=3), {}),
        ("material", [*ALBEDO, *KC, "--material", "Xx"], lambda: ss.bsdf(material="Xx", **KC_PY), {}),
        ("method", [*ALBEDO, *KC, "--method", "foo"], lambda: ss.bsdf(method="foo", **KC_PY), {"--method": "method"}),
        ("fresnel", [*ALBEDO, *KC, "--fresnel", "schlick"], lambda: ss.bsdf(fresnel="schlick", **KC_PY),
         {"--fresnel": "fresnel"}),
        ("theta_i", ["brdf", "albedo", *GGX, "--wavelength", "550", "--theta-i", "90"],
         lambda: ss.bsdf(**GGX_PY).albedo(90, 550), {"--theta-i": "theta_i_deg"}),
        ("wavelength", ["brdf", "albedo", *GGX, "--wavelength", "-5", "--theta-i", "10"],
         lambda: ss.bsdf(**GGX_PY).albedo(10, -5), {"--wavelength": "lambda_nm"}),
        ("inapplicable", ["brdf", "albedo", "--wavelength", "550", "--theta-i", "10", *GGX, "--smoothing", "0.5"],
         lambda: ss.bsdf(smoothing=0.5, **GGX_PY), {"--smoothing": "smoothing", "--model": "model"}),
        ("gamma", ["psd", "--model", "kc", "--sigma", "0.1", "--corr-length", "1", "--gamma", "0.5", "--zeta", "1"],
         lambda: ss.KCorrelation(0.1, 1, 0.5), {"--gamma": "gamma"}),
        ("length", ["acv", "--model", "gaussian", "--sigma", "1e12", "--corr-length", "1", "--r", "1"],
         lambda: ss.GaussianAcv(1e12, 1), {"--sigma": "sigma"}),
        ("orders", ["selfconv", "--gamma", "3", "--corr-length", "1", "--orders", "6000"],
         lambda: ss.KCorrelation(0.1, 1, 3).refit(6000), {"--orders": "max_order"}),
        ("threads", ["render", SCENE, "--threads", "1000", "-o", out / "r.exr"],
         lambda: ss.render(SCENE, threads=1000), {"--threads": "threads"}),
        ("exposure", ["render", SCENE, *DEFINES, "--exposure", "100", "-o", out / "r.exr"],
         lambda: ss.render(SCENE, params=SMALL, exposure=100), {"--exposure": "exposure"}),
        ("white balance", ["render", SCENE, *DEFINES, "--white-balance", "purple", "-o", out / "r.exr"],
         lambda: ss.render(SCENE, params=SMALL, white_balance="purple"), {"--white-balance": "white_balance"}),
        ("unused parameter", ["render", SCENE, *DEFINES, "-D", "colour=1", "-o", out / "r.exr"],
         lambda: ss.render(SCENE, params={**SMALL, "colour": 1}), {"-D colour": "params['colour']"}),
        ("height map", ["surface", "info", "/nonexistent/map.gwy"], lambda: ss.read_height_map("/nonexistent/map.gwy"),
         {}),
        ("scene", ["render", "/nonexistent/scene.xml", "-o", out / "r.exr"], lambda: ss.render("/nonexistent/scene.xml"),
         {}),
        ("photo", ["undistort", "/nonexistent/photo.png", "--camera", f["camera"], "-o", out / "u.exr"],
         lambda: ss.undistort("/nonexistent/photo.png", f["camera"]), {}),
        ("camera", ["undistort", f["blank"], "--camera", "/nonexistent/camera.yml", "-o", out / "u.exr"],
         lambda: ss.undistort(f["blank"], "/nonexistent/camera.yml"), {}),
        ("squares", ["calibrate", f["blank"], f["blank"], f["blank"], "--board", "chessboard", "--squares", "2x6",
                     "--square-length", "0.025", "-o", out / "c.yml"],
         lambda: ss.Board.chessboard((2, 6), 0.025), {"--squares": "squares"}),
        ("marker length", ["calibrate", f["blank"], "--board", "charuco", "--squares", "10x7", "--square-length",
                           "0.03", "--marker-length", "0.04", "-o", out / "c.yml"],
         lambda: ss.Board.charuco((10, 7), 0.03, 0.04),
         {"--marker-length": "marker_length_m", "--square-length": "square_length_m"}),
        ("dictionary", ["calibrate", f["blank"], "--board", "charuco", "--squares", "10x7", "--square-length",
                        "0.03", "--marker-length", "0.02", "--dictionary", "5X5_9", "-o", out / "c.yml"],
         lambda: ss.Board.charuco((10, 7), 0.03, 0.02, dictionary="5X5_9"), {}),
        ("no board", ["calibrate", f["blank"], f["blank"], f["blank"], "--board", "chessboard", "--squares", "9x6",
                      "--square-length", "0.025", "-o", out / "c.yml"],
         lambda: ss.calibrate([f["blank"]] * 3, ss.Board.chessboard((9, 6), 0.025)), {}),
        ("no marker", ["pose", f["blank"], "--camera", f["camera"], "--marker-length", "0.04", "-o", out / "p.json"],
         lambda: ss.pose(f["blank"], f["camera"], marker_length_m=0.04), {}),
        ("pose size", ["pose", f["small"], "--camera", f["camera"], "--marker-length", "0.04", "-o", out / "p.json"],
         lambda: ss.pose(f["small"], f["camera"], marker_length_m=0.04), {}),
        ("ambiguous", ["pose", grid, "--camera", f["camera"], "--marker-length", "0.04", "--dictionary", dictionary,
                       "--marker-id", "30", "-o", out / "p.json"],
         lambda: ss.pose(grid, f["camera"], marker_length_m=0.04, dictionary=dictionary, marker_id=30),
         {"--allow-ambiguous": "allow_ambiguous=True"}),
        ("linearize", ["colorcorrect", f["chart"], "--linearize", "log", "-o", out / "c.png", "--ccm", out / "c.json"],
         lambda: ss.colorcorrect(f["chart"], linearize="log"), {}),
        ("chart corners", ["colorcorrect", f["chart"], "--chart-corners", "0,0,700,0,10,10,0,10", "-o", out / "c.png",
                           "--ccm", out / "c.json"],
         lambda: ss.colorcorrect(f["chart"], chart_corners_px=[[0, 0], [700, 0], [10, 10], [0, 10]]),
         {"--chart-corners": "chart_corners_px"}),
        ("no chart", ["colorcorrect", f["blank"], "-o", out / "c.png", "--ccm", out / "c.json"],
         lambda: ss.colorcorrect(f["blank"]), {}),
        ("render size", ["compare", f["blank"], f["small"], "-o", out / "s.png"],
         lambda: ss.compare(f["blank"], [f["small"]]), {}),
    ]


CASE_IDS = ["sigma", "material", "method", "fresnel", "theta_i", "wavelength", "inapplicable", "gamma", "length",
            "orders", "threads", "exposure", "white balance", "unused parameter", "height map", "scene", "photo",
            "camera", "squares", "marker length", "dictionary", "no board", "no marker", "pose size", "ambiguous",
            "linearize", "chart corners", "no chart", "render size"]


@pytest.mark.parametrize("case", range(len(CASE_IDS)), ids=CASE_IDS)
def test_python_and_the_cli_give_the_same_message(case, files):
    files["out"].mkdir(exist_ok=True)
    name, args, call, renamed = cases(files)[case]
    assert name == CASE_IDS[case]
    expected = cli_error(args)
    for option, name in renamed.items():
        assert option in expected, f"the CLI's message does not name {option}: {expected}"
        expected = expected.replace(option, name)
    assert python_error(call) == expected
