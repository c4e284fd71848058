"""Issue 36, classes 2 and 3 in Python (docs/RELIABILITY.md): the CLI's checks hold here too, because they live in the
library (validity's criteria and synthesis counts, exact-1d's node and realization bounds); nothing is dropped
silently (an elliptical surface's lay in the profiles route); an argument whose default is not what "not given"
means is None until given, so that one that does not apply is an error even at its default value, as an option the
CLI is given; the library's messages name Python's arguments, not the CLI's options; a wrong argument type is surfscatter.Error naming the
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
            "realizations 1000000000000 (a done flag each) needs")


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


# Given means given (None is "not given"), as the CLI's options: an argument the chosen route does not use is an
# error even at its default value; each message names the Python argument, never a CLI option.
@pytest.mark.parametrize("call, expected", [
    (lambda: ss.validity_map(MAP, "perfect", [550], [0], map_pixels=256),
     "map_pixels synthesises maps from statistics (a KCorrelation or GaussianAcv): a height map is one realization"),
    (lambda: ss.validity_map(MAP, "perfect", [550], [0], seed=1), "seed synthesises maps from statistics"),
    (lambda: ss.validity_map(MAP, "perfect", [550], [0], realizations=1), "realizations synthesises maps"),
    (lambda: ss.validity_map(MAP, "perfect", [550], [0], map_size_um=0), "map_size_um synthesises maps"),
    (lambda: ss.validity_map(KC, "perfect", [550], [0], map_size_um=16, form="plane"),
     "form prepares a measured map (a HeightMap or a file)"),
    (lambda: ss.validity_map(KC, "perfect", [550], [0], map_size_um=16, lambda_c_um="auto"), "lambda_c_um prepares"),
    (lambda: ss.validity_map(KC, "perfect", [550], [0]), "map_size_um: give the side (um) of the maps"),
    (lambda: ss.validity_map(KC, "perfect", [550], [0], map_size_um=-1), "map_size_um must be"),
    (lambda: ss.KCorrelation(0.01, 1.0, 3.0, lay_angle_deg=0), "lay_angle_deg 0 needs corr_length_v"),
    (lambda: ss.GaussianAcv(0.01, 1.0, lay_angle_deg=0.0), "lay_angle_deg 0 needs corr_length_v"),
    (lambda: ss.export_rgl(ss.bsdf("ggx_stats", alpha=0.2, material="Au"), "/nonexistent/x.bsdf", phi_i_count=17),
     "phi_i_count applies to anisotropic surfaces only"),
    (lambda: ss.export_rgl(ss.bsdf("ggx_stats", alpha=0.2, material="Au"), "/nonexistent/x.bsdf", format="rgl-rgb",
                           lambda_step_nm=3.2), "lambda_step_nm applies to format rgl-spectral only"),
    (lambda: ss.export_rgl(ss.bsdf("ggx_stats", alpha=0.2, material="Au"), "/nonexistent/x.bsdf", theta_i_count=1),
     "theta_i_count must be in 2..256"),
    (lambda: ss.export_rgl(ss.bsdf("ggx_stats", alpha=0.2, material="Au"), "/nonexistent/x.bsdf", ndf_resolution=2),
     "ndf_resolution must be in 8..1024"),
    (lambda: ss.export_rgl(ss.bsdf("ggx_stats", alpha=0.2, material="Au"), "/nonexistent/x.bsdf", sample_resolution=2),
     "sample_resolution must be in 4..512"),
    (lambda: ss.export_rgl(ss.bsdf("ghs", surface=ss.KCorrelation(0.05, 1.0, 3.0, corr_length_v=2.0),
                                   material="Au"), "/nonexistent/x.bsdf", phi_i_count=2),
     "phi_i_count must be in 3..256"),
    (lambda: ss.export_rgl(ss.bsdf("ggx_stats", alpha=0.2, material="Au"), "/nonexistent/x.bsdf",
                           specular_lobe_deg=1), "specular_lobe_deg: the model ggx_stats has no coherent specular part"),
    (lambda: ss.export_rgl(ss.bsdf("ghs", surface=KC, material="Au"), "/nonexistent/x.bsdf", specular_lobe_deg=30),
     "specular_lobe_deg must be in (0, "),
], ids=["map_pixels", "seed", "realizations", "map_size_um", "form", "lambda_c_um", "no map_size_um",
        "negative map_size_um", "kc lay_angle_deg 0", "gaussian lay_angle_deg 0", "phi_i_count isotropic",
        "lambda_step_nm rgb", "theta_i_count", "ndf_resolution", "sample_resolution", "phi_i_count range",
        "specular_lobe_deg no delta", "specular_lobe_deg range"])
def test_an_argument_given_is_given_and_named_as_python_names_it(call, expected):
    start = time.monotonic()
    with pytest.raises(ss.Error) as raised:
        call()
    assert time.monotonic() - start < 20, "refused only after working"
    message = str(raised.value)
    assert expected in message, message
    assert "--" not in message, message


GHS = ss.bsdf("ghs", surface=KC, material="Au")


@pytest.mark.parametrize("keywords, expected", [
    (dict(lambda_step_nm=1e-300), "lambda_step_nm must be in [0.1, 640] nm, got 1e-300"),
    (dict(lambda_step_nm=1e300), "lambda_step_nm must be in [0.1, 640] nm"),
    (dict(lambda_step_nm=0.1, sample_resolution=512, theta_i_count=256),
     "available: use a smaller sample_resolution or theta_i_count or a larger lambda_step_nm"),
])
def test_export_rgl_bounds_its_tables_before_allocating(tmp_path, keywords, expected):
    path = tmp_path / "x.bsdf"
    refused(lambda: ss.export_rgl(GHS, str(path), **keywords), expected)
    assert not path.exists()


def test_messages_name_the_argument_given_and_what_to_do(tmp_path):
    """Class 4: the library's refusals name Python's arguments with their values, never a derived one."""
    refused(lambda: ss.validity(KC, "perfect", [550], [0], length_um=1e6, beam_width_um=4, realizations=2),
            "use a shorter length_um (now 1e+06 um) or a longer wavelengths_nm (now 550 nm)")
    refused(lambda: ss.validity(KC, "perfect", [1e-300], [0], **PROFILES),
            "wavelengths_nm must be between 0.1 and 100000000 nm, got 1e-300")
    zero = tmp_path / "zero.csv"
    zero.write_text("wavelength_nm,n,k\n400,0,0\n700,0,0\n")
    refused(lambda: ss.validity(KC, str(zero), [550], [0], **PROFILES),
            f"material {zero}: the refractive index at 550 nm is n = k = 0")
    refused(lambda: ss.validity_map(MAP, "perfect", [550], [0], form="bogus"),
            "form must be none, plane, poly2, poly3 or poly4, got 'bogus'")
    refused(lambda: ss.validity_map(KC, "perfect", [550], [0], map_size_um=16, tolerance=2),
            "tolerance must be in (0, 1), got 2")
    refused(lambda: ss.profile_models(KC, "perfect", 1e-300, 10, "s"),
            "wavelength_nm must be between 0.1 and 100000000 nm, got 1e-300")


@pytest.mark.parametrize("keywords, expected", [
    (dict(realizations=-1), "realizations must be at least 2, got -1"),
    (dict(realizations=1.5), "realizations must be a whole number, got 1.5"),
    (dict(realizations=2**70), "realizations is beyond the 64-bit range"),
    (dict(realizations=None, target_stderr_pct="5"), "target_stderr_pct must hold real numbers"),
    (dict(realizations=None, max_realizations="5"), "max_realizations must be a whole number, got '5'"),
])
def test_validity_names_a_wrong_count_or_type(keywords, expected):
    """Class 3: a count cast by pybind11 was TypeError "Unable to cast" naming no argument (-1 or 1.5 realizations)."""
    refused(lambda: ss.validity(KC, "perfect", [550], [0], **{**PROFILES, **keywords}), expected)
