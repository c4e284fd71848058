"""Issue 36, classes 2 and 3 in Python (docs/RELIABILITY.md): the CLI's checks hold here too, because they live in the
library (validity's criteria and synthesis counts, exact-1d's node and realization bounds); nothing is dropped
silently (an elliptical surface's lay in the profiles route); a wrong argument type is surfscatter.Error naming the
argument (or a TypeError), never RuntimeError "Unable to cast Python instance to C++ type"; sizes are refused before
any work starts (each call below returned at once or hung).
"""

import time

import pytest

import surfscatter as ss
from conftest import SOURCE_DIR

KC = ss.KCorrelation(0.01, 1.0, 3.0)
MAP = str(SOURCE_DIR / "examples" / "data" / "kc_surface.gsf")
PROFILES = dict(length_um=24, beam_width_um=4, realizations=2)


def refused(call, expected, error=ss.Error):
    """`call` raises `error` with one line holding `expected`, within a few seconds (no work done first)."""
    start = time.monotonic()
    with pytest.raises(error) as raised:
        call()
    assert time.monotonic() - start < 20, "refused only after working"
    message = str(raised.value)
    assert "\n" not in message and "Unable to cast" not in message, message
    assert expected in message, message


@pytest.mark.parametrize("keywords, expected", [
    (dict(tolerance=0), "tolerance must be in (0, 1), got 0"),
    (dict(tolerance=float("nan")), "tolerance must be in (0, 1), got nan"),
    (dict(bin_deg=45), "bin_deg must be in [0, 30] degrees, got 45"),
    (dict(max_reference_stderr=2), "max_reference_stderr must be in (0, 1], got 2"),
    (dict(threads=100000), "threads"),
])
def test_validity_checks_what_the_cli_checks(keywords, expected):
    refused(lambda: ss.validity(KC, "perfect", [550], [0], **PROFILES, **keywords), expected)


def test_validity_map_checks_what_the_cli_checks():
    refused(lambda: ss.validity_map(MAP, "perfect", [550], [0], bin_deg=31), "bin_deg must be in [0, 30] degrees")
    refused(lambda: ss.validity_map(MAP, "perfect", [550], [0], tolerance=1), "tolerance must be in (0, 1)")
    refused(lambda: ss.validity_map(MAP, "perfect", [550], [0], seed=5), "a height map is one realization")


def test_validity_keeps_an_elliptical_surface_out_of_the_profiles_route():
    elliptical = ss.KCorrelation(0.01, 1.0, 3.0, corr_length_v=3.0, lay_angle_deg=30)
    refused(lambda: ss.validity(elliptical, "perfect", [550], [0], **PROFILES),
            "surface is elliptical (corr_length_v 3, lay_angle_deg 30)")
    refused(lambda: ss.validity("kc", "perfect", [550], [0], **PROFILES), "surface must be a KCorrelation")


@pytest.mark.parametrize("keywords, expected", [
    (dict(map_pixels=1_000_000), "map_pixels must be in [8, 8192], got 1000000"),
    (dict(map_pixels=4), "map_pixels must be in [8, 8192], got 4"),
    (dict(realizations=1_000_000), "realizations must be in [1, 1000] maps, got 1000000"),
    (dict(realizations=0), "realizations must be in [1, 1000] maps, got 0"),
    (dict(realizations=-1), "realizations must be in [1, 1000] maps, got -1"),
])
def test_validity_map_bounds_its_synthesis_before_starting(keywords, expected):
    refused(lambda: ss.validity_map(KC, "perfect", [550], [0], map_size_um=16, **keywords), expected)


def test_validity_bounds_the_realizations_before_allocating():
    refused(lambda: ss.validity(KC, "perfect", [550], [0], length_um=24, beam_width_um=4, realizations=10**12),
            "the done flags of 1000000000000 realizations needs")


@pytest.mark.parametrize("keywords, expected", [
    (dict(fresnel=3), "fresnel must be a string, got 3"),
    (dict(models=["ghs_ssa"], ssa_form=b"energy"), "ssa_form must be a string, got b'energy'"),
    (dict(models=["ghs"], renormalization="yes"), "renormalization must be True or False, got 'yes'"),
    (dict(theta_o_deg="abc"), "theta_o_deg must hold real numbers"),
    (dict(theta_o_deg=[0, None]), "theta_o_deg must"),
])
def test_profile_models_names_a_wrong_argument_type(keywords, expected):
    refused(lambda: ss.profile_models(KC, "perfect", 550, 30, "s", **keywords), expected)


def test_statistics_name_a_wrong_argument_type():
    refused(lambda: ss.KCorrelation(0.01, 1.0, 3.0, corr_length_v="3"), "corr_length_v must hold real numbers")
    refused(lambda: ss.GaussianAcv(0.01, 1.0, corr_length_v=[1, 2]), "corr_length_v must be a single number")


def test_a_signature_mismatch_stays_a_type_error():
    # pybind11's own check of the declared types: a TypeError listing the signature, not a RuntimeError.
    with pytest.raises(TypeError, match="incompatible function arguments"):
        ss.profile_models(KC, "perfect", "550", 30, "s")


# The third call that ran on where the CLI stops: lists longer than the CLI's 10^5 items (validity's wavelengths,
# incidences and azimuths; profile_models' theta_o_deg, a fixed 1801-angle grid at the CLI) at ~0.5 ms an angle.
LONG = [0.0] * 100_001


def test_profile_models_bounds_its_angles():
    refused(lambda: ss.profile_models(KC, "perfect", 550, 30, "s", theta_o_deg=LONG), "theta_o: 100001 items, more than 100000")


def test_validity_bounds_its_lists():
    refused(lambda: ss.validity(KC, "perfect", [550] * 100_001, [0], **PROFILES), "wavelengths_nm: 100001 items")
    refused(lambda: ss.validity(KC, "perfect", [550], LONG, **PROFILES), "theta_i_deg: 100001 items")
    refused(lambda: ss.validity_map(MAP, "perfect", [550], [0], phi_i_deg=LONG), "phi_i_deg: 100001 items")


def test_synthesize_keeps_an_elliptical_surface_s_lay():
    """The lay was dropped (an isotropic map from an elliptical KCorrelation): LU = 1 um along x, LV = 4 um along y
    makes the map smoother along y, the mean squared step along y a fraction of that along x."""
    import numpy as np
    iso = ss.synthesize(ss.KCorrelation(0.05, 1.0, 3.0), size=128, spacing_um=0.25, seed=3).heights_um
    lay = ss.synthesize(ss.KCorrelation(0.05, 1.0, 3.0, corr_length_v=4.0), size=128, spacing_um=0.25, seed=3).heights_um
    def steps(h, axis):
        return np.mean(np.diff(h, axis=axis) ** 2)
    assert 0.8 < steps(iso, 0) / steps(iso, 1) < 1.25
    assert steps(lay, 0) / steps(lay, 1) < 0.5
    refused(lambda: ss.synthesize(KC, size=-3, spacing_um=0.25), "size must be n or (nx, ny)")
    refused(lambda: ss.synthesize(KC, size=(8, "9"), spacing_um=0.25), "size must be n or (nx, ny)")
    refused(lambda: ss.synthesize("kc", size=8, spacing_um=0.25), "statistics must be a KCorrelation or a GaussianAcv")
