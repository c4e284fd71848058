"""surfscatter.bsdf: eval and albedo against `surfscatter brdf eval/albedo`, eval/sample/pdf consistency on arrays,
broadcasting, options named as in the XML, and bad input."""

import re
import warnings

import numpy as np
import pytest

import surfscatter as ss
from conftest import CLI_RTOL, cli_csv, cli_values, numbers, run_cli, shared

KC = dict(sigma=0.05, corr_length=2.0, gamma=3.0)
KC_CLI = ["--psd", "kc", "--sigma", 0.05, "--corr-length", 2.0, "--gamma", 3.0]

# (keyword options of surfscatter.bsdf, the same as CLI options)
MODELS = [
    (dict(model="ghs", **KC), ["--model", "ghs", *KC_CLI]),
    (dict(model="ghs", method="refit", **KC), ["--model", "ghs", "--method", "refit", *KC_CLI]),
    (dict(model="ghs", fresnel="half", renormalization=False, **KC),
     ["--model", "ghs", "--fresnel", "half", "--no-renormalization", *KC_CLI]),
    (dict(model="ghs_ssa", **KC), ["--model", "ghs_ssa", *KC_CLI]),
    (dict(model="ghs_ssa", psd="gaussian", sigma=0.03, corr_length=1.0),
     ["--model", "ghs_ssa", "--psd", "gaussian", "--sigma", 0.03, "--corr-length", 1.0]),
    (dict(model="ggx_stats", alpha=0.2), ["--model", "ggx_stats", "--alpha", 0.2]),
    (dict(model="ggx_stats", alpha_from="smoothed", smoothing=0.1, **KC),
     ["--model", "ggx_stats", "--alpha-from", "smoothed", "--smoothing", 0.1, *KC_CLI]),
    (dict(model="two_scale", cutoff_wavelengths=50, **KC), ["--model", "two_scale", "--cutoff-wavelengths", 50, *KC_CLI]),
]
THETA_O = np.array([0.0, 15.0, 29.0, 30.0, 31.0, 60.0, 85.0])
PHI_O = np.array([0.0, 90.0, 170.0, 180.0])


@pytest.mark.parametrize("options, cli", MODELS, ids=lambda v: str(v))
def test_eval_and_albedo_equal_the_cli(options, cli):
    model = ss.bsdf(material="Au", **options)
    table = cli_csv("brdf", "eval", *cli, "--material", "Au", "--wavelength", 550, "--theta-i", 30,
                    "--theta-o", numbers(THETA_O), "--phi-o", numbers(PHI_O))
    wi = ss.direction(30.0, 0.0)
    wo = ss.direction(table["theta_o"], table["phi_o"])
    np.testing.assert_allclose(model.eval(wi, wo, 550.0), table["brdf"], rtol=CLI_RTOL, atol=1e-300)
    albedo = cli_values("brdf", "albedo", *cli, "--material", "Au", "--wavelength", 550, "--theta-i", 30)
    total, specular = model.albedo(30.0, 550.0)
    assert total == pytest.approx(albedo["albedo"], rel=CLI_RTOL)
    assert specular == pytest.approx(albedo["specular"], rel=CLI_RTOL, abs=1e-300)


def test_a_height_map_as_surface_equals_the_cli_with_surface():
    path = shared("realdata", "heightmaps", "opd-1.opd")
    table = cli_csv("brdf", "eval", "--model", "ghs", "--surface", path, "--material", "Ag", "--wavelength", 500,
                    "--theta-i", 20, "--theta-o", numbers(THETA_O))
    wi, wo = ss.direction(20.0, 0.0), ss.direction(table["theta_o"], table["phi_o"])
    expected = table["brdf"]
    from_path = ss.bsdf("ghs", surface=path, material="Ag")
    from_map = ss.bsdf("ghs", surface=ss.read_height_map(path), material="Ag")
    from_keyword = ss.bsdf("ghs", surface_file=str(path), material="Ag")
    for model in (from_path, from_map, from_keyword):
        np.testing.assert_allclose(model.eval(wi, wo, 500.0), expected, rtol=CLI_RTOL)
    assert from_map.options["psd"] == "file"


def test_the_measured_psd_of_a_height_map_equals_the_cli_and_reports_its_extrapolation():
    path = shared("realdata", "heightmaps", "opd-1.opd")
    table = cli_csv("brdf", "eval", "--model", "ghs", "--psd", "measured", "--surface", path, "--material", "Ag",
                    "--wavelength", 500, "--theta-i", 20, "--theta-o", numbers(THETA_O))
    wi, wo = ss.direction(20.0, 0.0), ss.direction(table["theta_o"], table["phi_o"])
    with pytest.warns(UserWarning) as warned:
        model = ss.bsdf("ghs", surface=ss.read_height_map(path), psd="measured", material="Ag")
    assert model.notes and [str(w.message) for w in warned] == model.notes
    assert model.options["psd"] == "measured"
    np.testing.assert_allclose(model.eval(wi, wo, 500.0), table["brdf"], rtol=CLI_RTOL)
    with pytest.raises(ss.Error, match="a height map surface takes psd 'file'"):
        ss.bsdf("ghs", surface=path, psd="kc")
    with pytest.raises(ss.Error, match="psd applies to a height map surface"):
        ss.bsdf("ghs", surface=ss.KCorrelation(**KC), psd="measured")


@pytest.mark.parametrize("options", [m[0] for m in MODELS], ids=lambda v: str(v))
def test_sample_weight_is_f_cos_over_pdf_and_pdf_matches(options):
    model = ss.bsdf(material="Cu", **options)
    rng = np.random.default_rng(11)
    n = 4000
    theta_i = np.repeat([0.0, 35.0, 70.0], n)
    wi = ss.direction(theta_i, rng.uniform(0, 360, theta_i.size))
    lam = rng.uniform(420, 680, theta_i.size)
    wo, weight, pdf, delta = model.sample(wi, lam, rng.random((theta_i.size, 3)))
    assert wo.shape == wi.shape and weight.shape == pdf.shape == delta.shape == lam.shape
    drawn = pdf > 0
    assert drawn.mean() > 0.9
    cont = drawn & ~delta
    f = model.eval(wi[cont], wo[cont], lam[cont])
    np.testing.assert_allclose(np.linalg.norm(wo[drawn], axis=-1), 1.0, rtol=1e-12)
    np.testing.assert_allclose(weight[cont], f * wo[cont, 2] / pdf[cont], rtol=1e-9)
    np.testing.assert_allclose(model.pdf(wi[cont], wo[cont], lam[cont]), pdf[cont], rtol=1e-9)
    if delta.any():
        mirror = wi[delta] * np.array([-1.0, -1.0, 1.0])
        np.testing.assert_allclose(wo[delta], mirror, atol=1e-15)
        np.testing.assert_allclose(pdf[delta], model.delta_probability(wi[delta], lam[delta]), rtol=1e-12)
        np.testing.assert_allclose(weight[delta], model.delta_reflectance(wi[delta], lam[delta]) / pdf[delta],
                                   rtol=1e-12)
    np.testing.assert_array_equal(weight[~drawn], 0.0)
    # The mean weight estimates the directional albedo (continuous + delta): within 4 standard errors.
    for t in (0.0, 35.0, 70.0):
        single = model.sample(ss.direction(t, 0.0), 550.0, rng.random((n, 3)))[1]
        error = 4 * single.std() / np.sqrt(n) + 1e-12
        assert single.mean() == pytest.approx(model.albedo(t, 550.0)[0], abs=error)


def test_broadcasting_matches_elementwise_calls():
    model = ss.bsdf("ghs", material="Au", **KC)
    wi = ss.direction(np.array([0.0, 20.0, 50.0])[:, None], 10.0)[:, :, None, :]  # (3, 1, 1, 3)
    wo = ss.direction(np.array([10.0, 25.0, 40.0, 70.0]), 190.0)[None, None, :, :]  # (1, 1, 4, 3)
    lam = np.array([450.0, 650.0])[None, :, None]  # (1, 2, 1)
    f = model.eval(wi, wo, lam)
    assert f.shape == (3, 2, 4)
    for i in range(3):
        for j in range(2):
            for k in range(4):
                assert f[i, j, k] == model.eval(wi[i, 0, 0], wo[0, 0, k], float(lam[0, j, 0]))
    assert np.isscalar(model.eval(wi[0, 0, 0], wo[0, 0, 0], 550.0))
    assert model.pdf(wi, wo, lam).shape == (3, 2, 4)
    total, specular = model.albedo(np.array([[0.0], [40.0]]), [500.0, 600.0, 700.0])
    assert total.shape == specular.shape == (2, 3)
    wo_s, weight, pdf, delta = model.sample(wi[:, :, 0, :], lam[:, :, 0], np.full((1, 1, 3), 0.5))
    assert wo_s.shape == (3, 2, 3) and weight.shape == (3, 2) and delta.dtype == bool
    assert model.eval(np.empty((0, 3)), ss.direction(0.0), 550.0).shape == (0,)
    # float32 and integer inputs are accepted; the result is float64.
    assert model.eval(wi.astype(np.float32), wo.astype(np.float32), 550).dtype == np.float64


def test_directions_below_the_surface_give_zero():
    model = ss.bsdf("ggx_stats", alpha=0.3)
    below = ss.direction(120.0, 0.0)
    assert model.eval(below, ss.direction(10.0, 180.0), 550.0) == 0.0
    wo, weight, pdf, delta = model.sample(below, 550.0, [0.5, 0.5, 0.5])
    assert weight == 0.0 and pdf == 0.0 and not delta
    np.testing.assert_array_equal(wo, 0.0)


def test_options_and_repr():
    model = ss.bsdf("two_scale", surface=ss.KCorrelation(**KC), material="Al", macro_ndf="beckmann",
                    cutoff_wavelengths=75)
    options = model.options
    assert options["model"] == "two_scale" and options["macro_ndf"] == "beckmann"
    assert options["cutoff_wavelengths"] == 75 and options["sigma"] == 0.05 and options["material"] == "Al"
    assert "two" in model.name.lower() or model.name
    assert "Al" in repr(model)
    gaussian = ss.bsdf("ghs_ssa", surface=ss.GaussianAcv(0.03, 1.0))
    assert gaussian.options["psd"] == "gaussian"
    assert not ss.bsdf("ggx_stats", alpha=0.1).is_pure_delta
    assert ss.bsdf("ggx_stats", alpha=0.1).name == "ggx_stats"
    assert "surface" in ss.bsdf.__doc__ and "lambda_nm" in ss.Bsdf.eval.__doc__


@pytest.mark.parametrize(
    "make, message",
    [
        (lambda: ss.bsdf("phong"), r"model must be one of ghs \| ghs_ssa \| ggx_stats \| two_scale, got 'phong'"),
        (lambda: ss.bsdf("ghs", **KC, roughness=3), "unknown option 'roughness'"),
        (lambda: ss.bsdf("ghs", **KC, method="fast"), "method"),
        (lambda: ss.bsdf("ghs", **KC, method=3), "method must be a string"),
        (lambda: ss.bsdf("ghs", **KC, epsilon="small"), "epsilon must hold real numbers"),
        (lambda: ss.bsdf("ghs", **KC, renormalization="no"), "renormalization must be True or False"),
        (lambda: ss.bsdf("ghs", sigma=np.nan, corr_length=2, gamma=3), "sigma must be a finite number"),
        (lambda: ss.bsdf("ghs", sigma=0.1, corr_length=2, gamma=0.5), r"gamma must be between 1.01 and 100 \(KC\), got 0.5"),
        (lambda: ss.bsdf("ghs"), r"bsdf\('ghs'\) needs surface=: KCorrelation"),
        (lambda: ss.bsdf("ghs", sigma=0, corr_length=2, gamma=3), r"sigma must be between 1e-09 and 1e\+09 um, got 0"),
        (lambda: ss.bsdf("ghs", surface=ss.KCorrelation(**KC), sigma=0.1), "not both"),
        (lambda: ss.bsdf("ghs", psd="measured"), "measured"),
        (lambda: ss.bsdf("ghs", surface=3.5), "surface must be a KCorrelation, a GaussianAcv, a MapStatistics"),
        (lambda: ss.bsdf("ghs", surface=ss.measured_statistics(ss.synthesize(ss.KCorrelation(**KC), 64, spacing_um=0.5)),
                         psd="measured"), "psd applies to a height map surface"),
        (lambda: ss.bsdf("ggx_stats"), r"needs surface=.*; or alpha= for a given roughness"),
        (lambda: ss.bsdf("ggx_stats", alpha_from="none"), "alpha must be between 0.0001 and 100, got 0"),
        (lambda: ss.bsdf("ggx_stats", alpha=0.1, material="Kryptonite"), "Kryptonite"),
        (lambda: ss.bsdf("ghs", surface="/nonexistent.gsf"), "/nonexistent.gsf"),
    ],
)
def test_bad_options_raise_error_naming_them(make, message):
    with pytest.raises(ss.Error, match=message):
        make()


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda b: b.eval([0, 0, 1], [0, 0, np.nan], 550), "wo must be a finite number, got nan"),
        (lambda b: b.eval([0, 0, 1], [0, 0, 1], np.inf), "lambda_nm must be a finite number, got inf"),
        (lambda b: b.eval([0, 0, 1], [0, 0, 1], [550, -1]), r"lambda_nm must be > 0 nm, got -1 at index \(1,\)"),
        (lambda b: b.eval([0, 0, 2], [0, 0, 1], 550), r"wi must be unit vectors, got \|wi\| = 2"),
        (lambda b: b.eval([0, 0, 1, 0], [0, 0, 1], 550), r"wi must have shape \(..., 3\), got shape \(4,\)"),
        (lambda b: b.eval(np.zeros((2, 3)) + [0, 0, 1], np.zeros((3, 3)) + [0, 0, 1], 550), "do not broadcast"),
        (lambda b: b.eval("up", [0, 0, 1], 550), "wi must hold real numbers"),
        (lambda b: b.eval([[0, 0, 1], [0, 1]], [0, 0, 1], 550), "wi must be an array of real numbers"),
        (lambda b: b.eval([True, False, True], [0, 0, 1], 550), "wi must hold real numbers, got dtype bool"),
        (lambda b: b.pdf([0, 0, 1], [0, 0, 1j], 550), "wo must hold real numbers, got dtype complex"),
        (lambda b: b.sample([0, 0, 1], 550, [0.5, 0.5, 1.0]), r"u must be in \[0, 1\), got 1"),
        (lambda b: b.sample([0, 0, 1], 550, [0.5, 0.5]), r"u must have shape \(..., 3\)"),
        (lambda b: b.sample([0, 0, 1], 550, [0.5, np.nan, 0.1]), "u must be a finite number"),
        (lambda b: b.albedo(90, 550), r"theta_i_deg must be in \[0, 90\) degrees, got 90"),
        (lambda b: b.albedo(30, 100), "outside the range"),
        (lambda b: b.delta_reflectance([0, 0, 1], None), "lambda_nm must hold real numbers"),
        (lambda b: b.eval(object(), [0, 0, 1], 550), "wi must hold real numbers"),
    ],
)
def test_bad_arrays_raise_error_naming_them(call, message):
    with pytest.raises(ss.Error, match=message):
        call(ss.bsdf("ghs", material="Au", **KC))


def test_direction_helper():
    w = ss.direction([0.0, 90.0], [0.0, 90.0])
    np.testing.assert_allclose(w, [[0, 0, 1], [0, 1, 0]], atol=1e-15)
    assert ss.direction(30.0).shape == (3,)
    with pytest.raises(ss.Error, match="theta_deg must be a finite number"):
        ss.direction(np.nan, 0.0)


def test_old_model_spellings_work_with_a_deprecation_warning():
    """One vocabulary (docs/CONVENTIONS.md): the scene plugins' names; 'ggx' and kebab-case values still work."""
    with pytest.warns(DeprecationWarning, match="model 'ggx' is an old spelling: write 'ggx_stats'"):
        old = ss.bsdf("ggx", alpha=0.2, material="Au")
    with pytest.warns(DeprecationWarning, match="truncation 'three-sigma' is an old spelling: write 'three_sigma'"):
        ss.bsdf("ghs", surface=ss.KCorrelation(**KC), method="refit", truncation="three-sigma")
    new = ss.bsdf("ggx_stats", alpha=0.2, material="Au")
    assert old.options == new.options and old.options["model"] == "ggx_stats" and old.options["alpha_from"] == "none"
    wi, wo = ss.direction(30.0), ss.direction(40.0, 180.0)
    assert old.eval(wi, wo, 550.0) == new.eval(wi, wo, 550.0)


def test_ggx_stats_takes_alpha_from_the_surface_by_default_and_says_what_works_for_gamma_3():
    model = ss.bsdf("ggx_stats", surface=ss.KCorrelation(sigma=0.2, corr_length=1.0, gamma=4.0))
    assert model.options["alpha_from"] == "measured"
    with pytest.raises(ss.Error, match=r"gamma = 3 diverges .*use alpha_from kc_link"):
        ss.bsdf("ggx_stats", surface=ss.KCorrelation(**KC), material="Au")
    assert ss.bsdf("ggx_stats", surface=ss.KCorrelation(**KC), alpha_from="kc_link").options["alpha_from"] == "kc_link"


def test_measured_statistics_is_a_surface_and_equals_psd_measured():
    path = shared("realdata", "heightmaps", "opd-1.opd")
    height_map = ss.read_height_map(path)
    psd = ss.measured_statistics(height_map)  # what psd 'measured' builds from the map
    assert len(repr(psd)) < 200 and "MapStatistics" in repr(psd)
    with pytest.warns(UserWarning, match="measured PSD"):
        from_psd = ss.bsdf("ghs", surface=psd, material="Ag")
    with pytest.warns(UserWarning, match="measured PSD"):
        from_map = ss.bsdf("ghs", surface=height_map, psd="measured", material="Ag")
    assert from_psd.options["psd"] == "measured"
    wi, wo = ss.direction(20.0), ss.direction(THETA_O, 180.0)
    np.testing.assert_allclose(from_psd.eval(wi, wo, 500.0), from_map.eval(wi, wo, 500.0), rtol=1e-12)


def test_measured_spectrum_2d_or_ring_as_at_the_cli():
    height_map = ss.synthesize(ss.KCorrelation(0.05, 1.0, 3.0), 128, spacing_um=0.1, seed=3)
    with pytest.warns(UserWarning, match="measured 2-D spectrum"):
        two_d = ss.bsdf("ghs", surface=height_map, psd="measured", material="perfect")
    with pytest.warns(UserWarning):
        ring = ss.bsdf("ghs", surface=height_map, psd="measured", measured_spectrum="ring", material="perfect")
    assert two_d.options["measured_spectrum"] == "2d" and ring.options["measured_spectrum"] == "ring"
    wi, wo = ss.direction(20.0), ss.direction(THETA_O, 180.0)
    assert not np.allclose(two_d.eval(wi, wo, 500.0), ring.eval(wi, wo, 500.0), rtol=1e-6)
    with pytest.raises(ss.Error, match="measured_spectrum does not apply to model ghs: used with psd measured only"):
        ss.bsdf("ghs", surface=ss.KCorrelation(**KC), measured_spectrum="ring", material="perfect")


def test_version_is_the_cli_version():
    assert ss.__version__ == run_cli("--version").split()[-1] and ss.__version__.count(".") == 2


# Elliptical surfaces (docs/SURFACE.md "Anisotropy"): KCorrelation / GaussianAcv with corr_length_v and lay_angle_deg,
# the same as the keyword form and as the CLI's --corr-length-v / --lay-angle.
ELLIPTICAL = dict(sigma=0.03, corr_length=2.0, gamma=2.5, corr_length_v=0.6, lay_angle_deg=35.0)


def test_elliptical_statistics_carry_their_lay_in_the_repr():
    kc = ss.KCorrelation(**ELLIPTICAL)
    assert (kc.corr_length_v, kc.lay_angle_deg) == (0.6, 35.0)
    assert "corr_length_v=0.6, lay_angle_deg=35" in repr(kc)
    assert ss.KCorrelation(0.03, 2.0, 2.5).corr_length_v is None
    assert repr(ss.KCorrelation(0.03, 2.0, 2.5)) == "surfscatter.KCorrelation(sigma=0.03, corr_length=2, gamma=2.5)"
    g = ss.GaussianAcv(0.03, 2.0, corr_length_v=1.0, lay_angle_deg=-20)
    assert (g.corr_length_v, g.lay_angle_deg) == (1.0, -20.0)
    model = ss.bsdf("ghs_ssa", surface=kc, material="Au", ssa_form="strict")
    assert "corr_length_v=0.6 lay_angle_deg=35" in repr(model)


def test_elliptical_surface_equals_keywords_and_cli():
    wi = ss.direction(40.0, 10.0)
    wo = ss.direction(np.array([10.0, 30.0, 60.0]), np.array([150.0, 200.0, 250.0]))
    from_object = ss.bsdf("ghs_ssa", surface=ss.KCorrelation(**ELLIPTICAL), material="Au", ssa_form="strict")
    from_keywords = ss.bsdf("ghs_ssa", material="Au", ssa_form="strict", **ELLIPTICAL)
    np.testing.assert_array_equal(from_object.eval(wi, wo, 633.0), from_keywords.eval(wi, wo, 633.0))
    isotropic = ss.bsdf("ghs_ssa", surface=ss.KCorrelation(0.03, 2.0, 2.5), material="Au", ssa_form="strict")
    assert not np.allclose(isotropic.eval(wi, wo, 633.0), from_object.eval(wi, wo, 633.0), rtol=1e-3)
    cli = cli_csv("brdf", "eval", "--model", "ghs_ssa", "--ssa-form", "strict", "--sigma", 0.03, "--corr-length", 2.0,
                  "--gamma", 2.5, "--corr-length-v", 0.6, "--lay-angle", 35, "--material", "Au", "--wavelength", 633,
                  "--theta-i", 40, "--phi-i", 10, "--theta-o", "10,30,60", "--phi-o", "150,200,250")
    got = from_object.eval(wi, ss.direction(cli["theta_o"], cli["phi_o"]), 633.0)
    np.testing.assert_allclose(got, cli["brdf"], rtol=CLI_RTOL)
    # LV = LU is the isotropic model itself.
    equal = ss.bsdf("ghs_ssa", surface=ss.KCorrelation(0.03, 2.0, 2.5, corr_length_v=2.0), material="Au",
                    ssa_form="strict")
    np.testing.assert_array_equal(equal.eval(wi, wo, 633.0), isotropic.eval(wi, wo, 633.0))


def test_elliptical_two_scale_equals_cli_and_isotropic_at_equal_lengths():
    wi = ss.direction(40.0, 10.0)
    wo = ss.direction(np.array([10.0, 40.0, 60.0]), np.array([150.0, 190.0, 250.0]))
    model = ss.bsdf("two_scale", surface=ss.KCorrelation(**ELLIPTICAL), material="Au")
    cli = cli_csv("brdf", "eval", "--model", "two_scale", "--sigma", 0.03, "--corr-length", 2.0, "--gamma", 2.5,
                  "--corr-length-v", 0.6, "--lay-angle", 35, "--material", "Au", "--wavelength", 633,
                  "--theta-i", 40, "--phi-i", 10, "--theta-o", "10,40,60", "--phi-o", "150,190,250")
    got = model.eval(wi, ss.direction(cli["theta_o"], cli["phi_o"]), 633.0)
    np.testing.assert_allclose(got, cli["brdf"], rtol=CLI_RTOL)
    isotropic = ss.bsdf("two_scale", surface=ss.KCorrelation(0.03, 2.0, 2.5), material="Au")
    equal = ss.bsdf("two_scale", surface=ss.KCorrelation(0.03, 2.0, 2.5, corr_length_v=2.0, lay_angle_deg=35.0),
                    material="Au")
    np.testing.assert_allclose(equal.eval(wi, wo, 633.0), isotropic.eval(wi, wo, 633.0), rtol=1e-9)
    assert not np.allclose(model.eval(wi, wo, 633.0), isotropic.eval(wi, wo, 633.0), rtol=1e-3)


def test_elliptical_bad_values_and_models():
    with pytest.raises(ss.Error, match="corr_length_v must be between"):
        ss.KCorrelation(0.03, 2.0, 2.5, corr_length_v=-1.0)
    with pytest.raises(ss.Error, match="lay_angle_deg must be a finite number"):
        ss.GaussianAcv(0.03, 2.0, corr_length_v=1.0, lay_angle_deg=float("nan"))
    with pytest.raises(ss.Error, match="lay_angle_deg 30 needs corr_length_v"):
        ss.KCorrelation(0.03, 2.0, 2.5, lay_angle_deg=30)
    with pytest.raises(ss.Error, match="lay_angle_deg does not apply to model ghs: used with corr_length_v only"):
        ss.bsdf("ghs", sigma=0.03, corr_length=2.0, gamma=2.5, lay_angle_deg=30, material="Au")
    with pytest.raises(ss.Error, match="give either surface= or"):
        ss.bsdf("ghs", surface=ss.KCorrelation(0.03, 2.0, 2.5), corr_length_v=1.0, material="Au")


def test_psd_fit_elliptical_equals_the_cli_and_reports_the_fit():
    path = shared("realdata", "heightmaps", "opd-1.opd")
    cli = cli_csv("brdf", "eval", "--model", "ghs_ssa", "--surface", path, "--psd-fit", "elliptical", "--material", "Ag",
                  "--wavelength", 500, "--theta-i", 20, "--phi-i", 40, "--theta-o", numbers(THETA_O),
                  "--phi-o", numbers(PHI_O))
    with pytest.warns(UserWarning) as warned:
        model = ss.bsdf("ghs_ssa", surface=path, psd_fit="elliptical", material="Ag")
    assert [str(w.message) for w in warned] == model.notes
    assert any("psd_fit elliptical of" in n and "the anisotropy is significant" in n for n in model.notes)
    assert model.options["psd_fit"] == "elliptical" and "psd_fit=elliptical" in repr(model)
    wi = ss.direction(20.0, 40.0)
    np.testing.assert_allclose(model.eval(wi, ss.direction(cli["theta_o"], cli["phi_o"]), 500.0), cli["brdf"],
                               rtol=CLI_RTOL)
    assert ss.bsdf("ghs", surface=path, material="Ag").options["psd_fit"] == "isotropic"
    with pytest.raises(ss.Error, match="psd_fit does not apply to model ghs: used with psd file"):
        ss.bsdf("ghs", surface=ss.KCorrelation(**KC), psd_fit="elliptical", material="Ag")
    with pytest.raises(ss.Error, match=re.escape("psd_fit must be one of isotropic | elliptical, got 'radial'")):
        ss.bsdf("ghs", surface=path, psd_fit="radial", material="Ag")
    with pytest.raises(ss.Error, match="elliptical KC fit: no elliptical KC fits"):
        ss.bsdf("ghs", surface=shared("realdata", "heightmaps", "di-1.di"), psd_fit="elliptical", material="Ag")


def test_measured_psd_eval_warns_of_directions_beyond_the_map():
    # As `brdf eval` (tests/cli/test_cli_brdf.cpp): a 0.5 um map resolves |zeta_x|, |zeta_y| <= 6.28 rad/um; at 550 nm
    # and theta_i 30 deg, theta_o 60 deg on the incidence side needs 15.6 rad/um, theta_o 0 needs 5.7.
    height_map = ss.synthesize(ss.KCorrelation(**KC), 64, spacing_um=0.5, seed=4)
    with pytest.warns(UserWarning):
        model = ss.bsdf("ghs", surface=height_map, psd="measured", material="perfect")
    wi = ss.direction(30.0, 0.0)
    with pytest.warns(UserWarning, match=r"^warning: 1 of 2 directions lie beyond the frequencies .* resolves"):
        values = model.eval(wi, ss.direction(np.array([0.0, 60.0]), np.array([0.0, 0.0])), 550.0)
    assert np.all(np.isfinite(values))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        model.eval(wi, ss.direction(np.array([10.0, 30.0, 50.0]), np.full(3, 180.0)), 550.0)
