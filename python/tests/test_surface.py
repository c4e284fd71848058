"""Surface statistics and height maps: against the CLI (psd, acv, selfconv, surface synth/info/fit), against closed
forms and a direct quadrature written here, numpy height maps with masks, and bad input."""

import numpy as np
import pytest

import surfscatter as ss
from conftest import CLI_RTOL, cli_csv, cli_values, numbers, run_cli, shared

ZETA = np.array([0.0, 0.01, 0.3, 1.0, 7.5, 200.0])
R = np.array([0.0, 1e-7, 0.05, 0.9, 3.0, 20.0])


@pytest.mark.parametrize("gamma", [1.5, 2.0, 3.0, 4.7])
def test_kc_psd_and_acv_equal_the_cli(gamma):
    kc = ss.KCorrelation(sigma=0.08, corr_length=1.7, gamma=gamma)
    model = ["--model", "kc", "--sigma", 0.08, "--corr-length", 1.7, "--gamma", gamma]
    np.testing.assert_allclose(kc.psd(ZETA), cli_csv("psd", *model, "--zeta", numbers(ZETA))["psd"], rtol=CLI_RTOL)
    np.testing.assert_allclose(kc.acv(R), cli_csv("acv", *model, "--r", numbers(R))["acv"], rtol=CLI_RTOL)


def test_gaussian_psd_and_acv_equal_the_cli_and_closed_forms():
    g = ss.GaussianAcv(sigma=0.2, corr_length=3.0)
    model = ["--model", "gaussian", "--sigma", 0.2, "--corr-length", 3.0]
    np.testing.assert_allclose(g.psd(ZETA), cli_csv("psd", *model, "--zeta", numbers(ZETA))["psd"], rtol=CLI_RTOL)
    np.testing.assert_allclose(g.acv(R), cli_csv("acv", *model, "--r", numbers(R))["acv"], rtol=CLI_RTOL)
    np.testing.assert_allclose(g.acv(R), 0.04 * np.exp(-(R / 3.0) ** 2), rtol=1e-14)
    np.testing.assert_allclose(g.psd_unit(ZETA), 9.0 / (4 * np.pi) * np.exp(-9.0 * ZETA**2 / 4), rtol=1e-14)
    assert g.mean_square_slope() == pytest.approx(4 * 0.04 / 9.0, rel=1e-12)


def test_kc_closed_forms_and_abc():
    kc = ss.KCorrelation(0.1, 2.0, 3.0)
    unit = 2.0 * 4.0 / (2 * np.pi) * (1 + 4.0 * ZETA**2) ** -2.0
    np.testing.assert_allclose(kc.psd_unit(ZETA), unit, rtol=1e-13)
    np.testing.assert_allclose(kc.radial_cdf(ZETA), 1 - (1 + 4.0 * ZETA**2) ** -1.0, rtol=1e-13, atol=1e-16)
    u = np.array([0.0, 0.2, 0.9])
    np.testing.assert_allclose(kc.radial_cdf(kc.inverse_radial_cdf(u)), u, atol=1e-13)
    assert kc.acv_normalized(0.0) == pytest.approx(1.0, rel=1e-14)
    abc = kc.abc
    assert abc["c"] == 3.0 and abc["b"] == pytest.approx(2 * np.pi * 2.0)
    back = ss.KCorrelation.from_abc(**abc)
    assert (back.sigma_h, back.correlation_length, back.gamma) == pytest.approx((0.1, 2.0, 3.0), rel=1e-13)


def visible_disc_mass_by_quadrature(stats, theta_deg, lambda_nm, nodes=600):
    """Mass of P-hat over the disc of radius k about k sin(theta) e_x, by Gauss-Legendre in polar coordinates
    about the disc's centre: independent of the library's radial-CDF-plus-annulus rule."""
    k = 2 * np.pi * 1000 / lambda_nm
    centre = k * np.sin(np.radians(theta_deg))
    x, w = np.polynomial.legendre.leggauss(nodes)
    rho, w_rho = 0.5 * k * (x + 1), 0.5 * k * w
    phi, w_phi = np.pi * (x + 1), np.pi * w
    zx = centre + rho[:, None] * np.cos(phi)[None, :]
    zy = rho[:, None] * np.sin(phi)[None, :]
    values = stats.psd_unit(np.hypot(zx, zy))
    return float(np.sum(values * (rho * w_rho)[:, None] * w_phi[None, :]))


@pytest.mark.parametrize("theta_deg", [0.0, 30.0, 60.0])
def test_relevant_roughness_against_direct_quadrature(theta_deg):
    kc = ss.KCorrelation(0.05, 0.3, 3.0)
    mass = visible_disc_mass_by_quadrature(kc, theta_deg, 550.0)
    assert kc.visible_disc_mass(theta_deg, 550.0) == pytest.approx(mass, rel=1e-6)
    assert kc.relevant_roughness(theta_deg, 550.0) == pytest.approx(0.05 * np.sqrt(mass), rel=1e-6)


def test_relevant_roughness_broadcasts_and_tis_follows_it():
    kc = ss.KCorrelation(0.05, 2.0, 3.0)
    theta = np.array([0.0, 45.0, 80.0])[:, None]
    lam = np.array([400.0, 550.0, 700.0, 900.0])
    sigma_rel = kc.relevant_roughness(theta, lam)
    assert sigma_rel.shape == (3, 4)
    assert sigma_rel[1, 2] == kc.relevant_roughness(45.0, 700.0)
    k = 2 * np.pi * 1000 / 550.0
    assert kc.relevant_roughness(0.0, 550.0) == pytest.approx(0.05 * np.sqrt(1 - 1 / (1 + 4 * k**2)), rel=1e-10)
    tis = kc.total_integrated_scatter(0.0, 550.0)
    assert tis == pytest.approx(1 - np.exp(-(4 * np.pi * kc.relevant_roughness(0.0, 550.0) * 1000 / 550.0) ** 2))


def test_refit_equals_the_cli():
    out = run_cli("selfconv", "--gamma", 3, "--corr-length", 1.5, "--orders", 13).splitlines()
    assert out[0].startswith("x = ")
    table = np.array([[float(v) for v in line.split(",")] for line in out[2:]])
    fit = ss.KCorrelation(1.0, 1.5, 3.0).refit(13)
    assert fit.exponent_x == pytest.approx(float(out[0][4:]), rel=CLI_RTOL)
    np.testing.assert_allclose(fit.corr_length_um, table[:, 1], rtol=CLI_RTOL)
    np.testing.assert_allclose(fit.misfit, table[:, 2], rtol=CLI_RTOL, atol=1e-15)


def test_self_convolutions_of_gamma_2_are_kc_with_l_over_m():
    # For gamma = 2 the m-fold convolution of the KC PSD is exactly KC(L/m) (THEORY.md 2.3).
    table = ss.KCorrelation(1.0, 2.0, 2.0).self_convolution(20)
    assert table.max_order == 20
    zeta = np.geomspace(1e-2, 100, 25)
    for m in (1, 2, 7, 20):
        lm = 2.0 / m
        exact = lm**2 / (2 * np.pi) * (1 + lm**2 * zeta**2) ** -1.5
        np.testing.assert_allclose(table.psd_unit(m, zeta), exact, rtol=1e-7)
    u = np.array([0.1, 0.5, 0.99])
    np.testing.assert_allclose(table.radial_cdf(3, table.inverse_radial_cdf(3, u)), u, atol=1e-8)
    with pytest.raises(ss.Error, match="order 21 outside the table's 1..20"):
        table.psd_unit(21, 1.0)


def test_tabulated_psd_interpolates_its_samples():
    zeta = np.geomspace(0.01, 100, 30)
    kc = ss.KCorrelation(0.1, 2.0, 3.0)
    tab = ss.TabulatedPsd(zeta, kc.psd(zeta))
    np.testing.assert_allclose(tab.psd(zeta[1:-1]), kc.psd(zeta[1:-1]), rtol=1e-10)
    assert tab.sigma_h == pytest.approx(0.1, rel=0.01)
    with pytest.raises(ss.Error, match="zeta and psd must be 1-D arrays of the same length"):
        ss.TabulatedPsd(zeta, kc.psd(zeta)[:-1])
    with pytest.raises(ss.Error, match="psd must be > 0"):
        ss.TabulatedPsd(zeta, -kc.psd(zeta))


def test_synthesize_equals_the_cli(tmp_path):
    gsf = tmp_path / "synth.gsf"
    run_cli("surface", "synth", "--sigma", 0.1, "--corr-length", 2, "--gamma", 3, "--size", 64, "--spacing", 0.25,
            "--seed", 7, "-o", gsf)
    ours = ss.synthesize(ss.KCorrelation(0.1, 2.0, 3.0), 64, spacing_um=0.25, seed=7)
    theirs = ss.read_height_map(gsf)
    assert ours.heights_um.shape == (64, 64) and ours.valid is None
    # The GSF stores float32 metres.
    np.testing.assert_allclose(ours.heights_um, theirs.heights_um, rtol=0, atol=1e-7 * np.abs(ours.heights_um).max())
    assert (theirs.spacing_x_um, theirs.spacing_y_um) == pytest.approx((0.25, 0.25))
    again = ss.synthesize(ss.KCorrelation(0.1, 2.0, 3.0), 64, spacing_um=0.25, seed=7)
    np.testing.assert_array_equal(again.heights_um, ours.heights_um)
    wide = ss.synthesize(ss.GaussianAcv(0.1, 2.0), (64, 32), spacing_um=0.5)
    assert wide.heights_um.shape == (32, 64) and (wide.nx, wide.ny) == (64, 32)


def test_fit_of_a_real_file_equals_the_cli_and_of_its_numpy_array():
    path = shared("realdata", "heightmaps", "opd-1.opd")
    cli = cli_values("surface", "fit", path)
    # The CLI fits the map as every consumer prepares it (docs/HEIGHTMAPS.md "Preparation"): so does Python.
    fit = ss.fit_surface(ss.read_height_map(path).prepare()["map"], form="none")
    for name in ("sigma_h", "corr_length", "gamma", "rms_slope", "zeta_min", "zeta_max", "log_residual_rms"):
        assert getattr(fit, name) == pytest.approx(cli[name], rel=CLI_RTOL), name
    assert fit.rms_slope_psd == pytest.approx(cli["rms_slope_psd"], rel=CLI_RTOL)
    assert fit.rms_height_map == pytest.approx(cli["rms_height_map"], rel=CLI_RTOL)
    # The same data as a user's own numpy array with its mask: the same fit, without a file.
    read = ss.read_height_map(path)
    assert read.valid is not None and 0.999 < read.valid_fraction < 1
    heights = np.where(read.valid, read.heights_um, np.nan)
    own = ss.HeightMap(heights, (read.spacing_x_um, read.spacing_y_um), valid=read.valid)
    again = ss.fit_surface(own.prepare()["map"], form="none")
    assert (again.sigma_h, again.corr_length, again.gamma) == (fit.sigma_h, fit.corr_length, fit.gamma)
    radial = fit.radial
    assert radial["zeta"].shape == radial["psd"].shape == radial["count"].shape
    assert fit.rings == np.count_nonzero((radial["zeta"] >= fit.zeta_min) & (radial["zeta"] <= fit.zeta_max))
    kc = fit.statistics
    assert kc.gamma == fit.gamma and kc.sigma_h == fit.sigma_h
    assert fit.psd2d["values"].shape == (read.ny, read.nx // 2 + 1)


def test_surface_info_figures_equal_the_cli():
    path = shared("realdata", "heightmaps", "opd-1.opd")
    cli = cli_values("surface", "info", path, "--form", "poly2")
    h = ss.read_height_map(path)
    moments = h.moments(form="poly2")
    acv = h.acv_measures(form="poly2")
    assert moments["rms"] == pytest.approx(cli["rms_height_um"], rel=CLI_RTOL)
    assert moments["skewness"] == pytest.approx(cli["skewness"], rel=CLI_RTOL)
    assert moments["kurtosis"] == pytest.approx(cli["kurtosis"], rel=CLI_RTOL)
    assert h.rms_slope(form="poly2") == pytest.approx(cli["rms_slope"], rel=CLI_RTOL)
    assert acv["correlation_length_um"] == pytest.approx(cli["correlation_length_um"], rel=CLI_RTOL)
    assert acv["texture_aspect_ratio"] == pytest.approx(cli["texture_aspect_ratio"], rel=CLI_RTOL)
    assert h.source["format"] == "Wyko OPD files (.opd)"
    assert h.remove_form("poly2").rms_height("none") == pytest.approx(moments["rms"], rel=1e-12)


def test_measured_statistics_follow_the_surface_they_were_drawn_from():
    kc = ss.KCorrelation(0.1, 2.0, 3.0)
    surface = ss.synthesize(kc, 512, spacing_um=0.25, seed=3)
    measured = ss.measured_statistics(surface, form="none")
    assert isinstance(measured, ss.MapStatistics)
    assert measured.periodic  # synthesised maps wrap around
    assert measured.map_rms == pytest.approx(surface.rms_height("none"), rel=1e-12)
    assert measured.sigma_h == pytest.approx(measured.map_rms, rel=0.02)
    zeta = np.geomspace(0.5, 5.0, 7)
    # Each ring a mean of its own periodogram values: within four standard errors of the truth.
    tolerance = 4.0 / np.sqrt(measured.ring_samples(zeta))
    assert np.all(np.abs(measured.psd(zeta) / kc.psd(zeta) - 1.0) < tolerance)
    assert "MapStatistics sigma=" in repr(measured) and len(repr(measured)) < 200


def test_height_map_round_trip_through_gsf_with_invalid_points(tmp_path):
    rng = np.random.default_rng(5)
    heights = rng.normal(0, 0.01, (16, 24))
    valid = np.ones_like(heights, dtype=bool)
    valid[3, 4] = valid[10, 20] = False
    heights[~valid] = np.nan
    h = ss.HeightMap(heights, (0.5, 0.25), valid=valid, origin="test")
    assert (h.nx, h.ny, h.spacing_x_um, h.spacing_y_um) == (24, 16, 0.5, 0.25)
    assert h.valid_fraction == pytest.approx(1 - 2 / heights.size)
    h.write(tmp_path / "map.gsf")
    back = ss.read_height_map(tmp_path / "map.gsf")
    np.testing.assert_array_equal(back.valid, valid)
    np.testing.assert_allclose(back.heights_um[valid], heights[valid], rtol=1e-6)
    with pytest.raises(ss.Error, match="must name a .gsf or .gwy file"):
        h.write(tmp_path / "map.png")


@pytest.mark.parametrize(
    "make, message",
    [
        (lambda: ss.KCorrelation(-1, 2, 3), r"sigma must be between 1e-09 and 1e\+09 um, got -1"),
        (lambda: ss.KCorrelation(0.1, 2, 0.5), r"gamma must be between 1.01 and 100 \(KC\), got 0.5"),
        (lambda: ss.KCorrelation(0.1, np.nan, 3), r"corr_length must be between 1e-09 and 1e\+09 um, got nan"),
        (lambda: ss.KCorrelation(0.1, 2, 3).psd(-1.0), "zeta must be >= 0, got -1"),
        (lambda: ss.KCorrelation(0.1, 2, 3).acv([0, np.inf]), r"r_um must be a finite number, got inf at index \(1,\)"),
        (lambda: ss.KCorrelation(0.1, 2, 3).relevant_roughness(90, 550), r"theta_i_deg must be in \[0, 90\) degrees"),
        (lambda: ss.KCorrelation(0.1, 2, 3).relevant_roughness([[0, 1]], [1, 2, 3]), "do not broadcast"),
        (lambda: ss.HeightMap(np.full((16, 16), np.nan), 1.0),
         r"heights_um is NaN at column 0, row 0: mark the points without data invalid, "
         r"HeightMap\(heights_um, spacing_um, valid=~np.isnan\(heights_um\)\)"),
        (lambda: ss.HeightMap(np.full((16, 16), np.inf), 1.0), "finite"),
        (lambda: ss.HeightMap(np.zeros(16), 1.0), "heights_um must be a 2-D array"),
        (lambda: ss.HeightMap(np.zeros((16, 16)), -1.0), "spacing_um must be > 0"),
        (lambda: ss.HeightMap(np.zeros((16, 16)), (1.0, 2.0, 3.0)), "one number or a pair"),
        (lambda: ss.HeightMap(np.zeros((16, 16)), 1.0, valid=np.ones((16, 16))), "valid must be a boolean array"),
        (lambda: ss.HeightMap(np.zeros((16, 16)), 1.0, valid=np.ones((8, 16), bool)), "valid must have the shape"),
        (lambda: ss.HeightMap(np.zeros((16, 16)), 1.0, valid=np.zeros((16, 16), bool)), "valid"),
        (lambda: ss.HeightMap(np.zeros((16, 16), complex), 1.0), "heights_um must hold real numbers"),
        (lambda: ss.synthesize(ss.KCorrelation(0.1, 2, 3), 4, spacing_um=1.0), "at least 8"),
        (lambda: ss.synthesize(ss.KCorrelation(0.1, 2, 3), 2.5, spacing_um=1.0), "size must be n or"),
        (lambda: ss.read_height_map("/nonexistent/map.gsf"), "/nonexistent/map.gsf"),
        # Read by Gwyddion's 'jpeg' module (its modules load inside Python too), but not a height map.
        (lambda: ss.read_height_map(shared("realdata", "photos", "gboriginal.jpg")), "no height channel"),
        (lambda: ss.fit_surface(ss.synthesize(ss.KCorrelation(0.1, 2, 3), 16, spacing_um=1.0), form="sphere"),
         "form must be none, plane"),
    ],
)
def test_bad_input_raises_error_naming_it(make, message):
    with pytest.raises(ss.Error, match=message):
        make()


def test_elliptical_fit_recovers_the_lay_and_equals_the_cli(tmp_path):
    gsf = str(tmp_path / "brushed.gsf")
    run_cli("surface", "synth", "--sigma", 0.05, "--corr-length", 8, "--corr-length-v", 2, "--lay-angle", 30,
            "--gamma", 2.5, "--size", 256, "--spacing", 1, "--seed", 4, "-o", gsf)
    cli = cli_values("surface", "fit", gsf)
    h = ss.read_height_map(gsf)
    e = ss.fit_elliptical(h)
    for name, line in (("sigma_h", "elliptical_sigma_h"), ("corr_length", "elliptical_corr_length"),
                       ("corr_length_v", "elliptical_corr_length_v"), ("gamma", "elliptical_gamma"),
                       ("lay_angle_deg", "elliptical_lay_angle"), ("misfit", "elliptical_log_residual_rms"),
                       ("statistical_floor", "elliptical_statistical_floor")):
        assert getattr(e, name) == pytest.approx(cli[line], rel=CLI_RTOL), name
    assert e.anisotropic
    # The truth within 4 standard errors.
    assert abs(e.corr_length - 8) < 4 * e.corr_length_error
    assert abs(e.corr_length_v - 2) < 4 * e.corr_length_v_error
    assert abs(e.lay_angle_deg - 30) < 4 * e.lay_angle_error_deg
    fit = ss.fit_surface(h)
    assert fit.corr_length_v == e.corr_length_v and fit.lay_angle_deg == e.lay_angle_deg
    assert fit.elliptical.gamma == e.gamma


def test_elliptical_fit_refuses_a_map_without_a_knee():
    # KC with L far beyond the map: no knee in the band along either axis.
    h = ss.synthesize(ss.KCorrelation(0.1, 500.0, 2.5), 64, spacing_um=1.0)
    with pytest.raises(ss.Error, match="elliptical KC fit"):
        ss.fit_elliptical(h)
