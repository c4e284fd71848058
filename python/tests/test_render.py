"""surfscatter.render against `surfscatter render` (the same EXR), its XYZ output, overrides, Ctrl-C, bad input."""

import os
import signal
import threading

import numpy as np
import pytest

import surfscatter as ss
from conftest import SOURCE_DIR, run_cli

SCENE = SOURCE_DIR / "scenes" / "photo-setup" / "scene.xml"
SMALL = {"view": 1, "width": 48, "height": 36, "model": "ghs", "sigma": 0.15, "corr_length": 4, "gamma": 4}

# XYZ -> linear sRGB, IEC 61966-2-1 (D65), written out here rather than taken from the library.
XYZ_TO_SRGB = np.array([[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]])


def test_render_equals_the_cli_exr(tmp_path):
    exr = tmp_path / "view1.exr"
    run_cli("render", SCENE, *sum((["-D", f"{k}={v}"] for k, v in SMALL.items()), []), "--spp", 4, "--seed", 9,
            "--quiet", "-o", exr)
    result = ss.render(SCENE, spp=4, params=SMALL, seed=9)
    rgb = result["rgb"]
    assert rgb.dtype == np.float32 and rgb.shape == (36, 48, 3)
    assert result["xyz"].dtype == np.float32 and result["xyz"].shape == (36, 48, 3)
    assert result["alpha"].dtype == np.float32 and result["alpha"].shape == (36, 48)
    assert np.isfinite(result["alpha"]).all()
    assert result["spp"] == result["max_spp"] == 4 and not result["interrupted"] and result["rays"] > 0
    # The CLI's EXR holds half floats (hdrfilm's default component_format float16, as Mitsuba's).
    np.testing.assert_array_equal(rgb.astype(np.float16).astype(np.float32), ss.read_photo(exr))
    assert np.isfinite(rgb).all() and rgb.max() > 0
    # Deterministic whatever the thread count.
    np.testing.assert_array_equal(ss.render(SCENE, spp=4, params=SMALL, seed=9, threads=1)["rgb"], rgb)


def test_xyz_is_the_film_before_white_balance_and_exposure():
    plain = ss.render(SCENE, spp=2, params=SMALL, seed=1, white_balance="d65", exposure=0.0)
    expected = np.einsum("ij,hwj->hwi", XYZ_TO_SRGB, plain["xyz"].astype(np.float64))
    np.testing.assert_allclose(plain["rgb"], expected, rtol=2e-3, atol=1e-6)
    brighter = ss.render(SCENE, spp=2, params=SMALL, seed=1, white_balance="d65", exposure=1.0)
    np.testing.assert_allclose(brighter["rgb"], 2 * plain["rgb"], rtol=1e-6)
    np.testing.assert_array_equal(brighter["xyz"], plain["xyz"])
    warm = ss.render(SCENE, spp=2, params=SMALL, seed=1)  # the scene's own 2700 K white balance
    assert not np.allclose(warm["rgb"], plain["rgb"])


def test_ctrl_c_stops_the_render_and_keeps_what_it_has():
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.warns(RuntimeWarning, match="interrupted"):
            result = ss.render(SCENE, spp=3200, params=SMALL, seed=2)  # passes of 200 spp
    finally:
        timer.cancel()
    assert result["interrupted"] and result["spp"] <= result["max_spp"] and 0 < result["max_spp"] < 3200
    assert np.isfinite(result["rgb"]).all() and result["rgb"].max() > 0
    # The flag does not outlive the call.
    assert not ss.render(SCENE, spp=1, params=SMALL, seed=2)["interrupted"]


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(scene="/nonexistent/scene.xml"), "/nonexistent/scene.xml"),
        (dict(scene=SCENE, params={"view": 9}), "view9.xml"),
        (dict(scene=SCENE, params={"model": "phong"}), "metal_phong.xml"),
        (dict(scene=SCENE, params={"sigma": -1}), "sigma"),
        (dict(scene=SCENE, params=["view", 1]), "params must be a dict"),
        (dict(scene=SCENE, params={"view": [1]}), r"params\['view'\] must be a string or a number"),
        (dict(scene=SCENE, params={"bad name": 1}), r"params\['bad name'\]: a parameter name has letters, digits"),
        (dict(scene=SCENE, params={**SMALL, "unused": 1}), r"never uses \$unused"),
        (dict(scene=SCENE, spp=0), "spp must be positive, got 0"),
        (dict(scene=SCENE, threads=-2), "threads must be"),
        (dict(scene=SCENE, seed=-1), "seed must be >= 0, got -1"),
        (dict(scene=SCENE, params=SMALL, spp=1, exposure=float("nan")), "exposure must be between -64 and 64 stops"),
        (dict(scene=SCENE, params=SMALL, spp=1, white_balance="purple"), "white_balance: .*'purple'"),
        (dict(scene=42), "scene must be a path"),
    ],
)
def test_bad_input_raises_error_naming_it(kwargs, message):
    with pytest.raises(ss.Error, match=message):
        ss.render(**kwargs)


def test_a_height_map_renders_the_plate_as_the_cli_does(tmp_path):
    # params surface_file alone makes photo-setup's metal read the map (render/scene_parameters.hpp), as -D does.
    params = {"width": 24, "height": 18, "model": "ggx_stats", "form": "poly2",
              "surface_file": str(SOURCE_DIR / "examples" / "data" / "kc_surface.gsf")}
    exr = tmp_path / "map.exr"
    run_cli("render", SCENE, *sum((["-D", f"{k}={v}"] for k, v in params.items()), []), "--spp", 1, "--seed", 3,
            "--quiet", "-o", exr)
    rgb = ss.render(SCENE, spp=1, params=params, seed=3)["rgb"]
    np.testing.assert_array_equal(rgb.astype(np.float16).astype(np.float32), ss.read_photo(exr))
    with pytest.raises(ss.Error, match=r"surface_map\.xml:\d+: file not found: .*absent\.gsf"):
        ss.render(SCENE, spp=1, params={**params, "surface_file": str(tmp_path / "absent.gsf")})
