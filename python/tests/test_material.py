"""surfscatter.Conductor against `surfscatter ior` and `surfscatter fresnel`, broadcasting and bad input."""

import numpy as np
import pytest

import surfscatter as ss
from conftest import CLI_RTOL, cli_csv, numbers, shared

WAVELENGTHS = np.array([380.0, 450.5, 550.0, 633.0, 800.0])


@pytest.mark.parametrize("metal", ["Au", "Ag", "Al", "Cu"])
def test_ior_equals_the_cli(metal):
    table = cli_csv("ior", "--material", metal, "--wavelength", numbers(WAVELENGTHS))
    n = ss.Conductor(metal).ior(WAVELENGTHS)
    assert n.dtype == np.complex128 and n.shape == WAVELENGTHS.shape
    np.testing.assert_allclose(n.real, table["n"], rtol=CLI_RTOL)
    np.testing.assert_allclose(n.imag, table["k"], rtol=CLI_RTOL)


def test_ior_from_a_refractiveindex_info_file():
    path = shared("refractiveindex", "Au_Johnson.yml")
    conductor = ss.Conductor(path)
    table = cli_csv("ior", "--material", path, "--wavelength", "500,600")
    np.testing.assert_allclose(conductor.ior([500, 600]).imag, table["k"], rtol=CLI_RTOL)
    assert conductor.name and not conductor.is_perfect


@pytest.mark.parametrize("polarization", ["s", "p", "unpolarized"])
def test_reflectance_equals_the_cli(polarization):
    theta_deg = np.array([0.0, 20.0, 45.0, 70.0, 89.0])
    table = cli_csv("fresnel", "--material", "Cu", "--wavelength", "550", "--theta", numbers(theta_deg),
                    "--polarization", polarization)
    r = ss.Conductor("Cu").reflectance(np.cos(np.radians(theta_deg)), 550, polarization=polarization)
    np.testing.assert_allclose(r, table["R"], rtol=CLI_RTOL)


def test_reflectance_broadcasts_and_scalars_stay_scalars():
    au = ss.Conductor("Au")
    cos_theta = np.linspace(0.1, 1, 4)[:, None]
    r = au.reflectance(cos_theta, WAVELENGTHS)
    assert r.shape == (4, WAVELENGTHS.size)
    for i in range(4):
        for j, lam in enumerate(WAVELENGTHS):
            assert r[i, j] == au.reflectance(float(cos_theta[i, 0]), float(lam))
    assert np.isscalar(au.reflectance(0.5, 550))
    assert np.isscalar(au.ior(550))


def test_perfect_conductor():
    perfect = ss.Conductor("perfect")
    assert perfect.is_perfect
    np.testing.assert_array_equal(perfect.reflectance([0, 0.5, 1], 550), 1.0)
    with pytest.raises(ss.Error, match="perfect conductor has no finite refractive index"):
        perfect.ior(550)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda c: c.ior(np.nan), "lambda_nm must be a finite number, got nan"),
        (lambda c: c.ior([500, np.inf]), r"lambda_nm must be a finite number, got inf at index \(1,\)"),
        (lambda c: c.ior(-5), "lambda_nm must be > 0 nm, got -5"),
        (lambda c: c.ior(200), "wavelength 200 nm is outside the range"),
        (lambda c: c.ior("500"), "lambda_nm must hold real numbers"),
        (lambda c: c.ior([[500], [500, 600]]), "lambda_nm must be an array of real numbers"),
        (lambda c: c.reflectance(1.5, 500), r"cos_theta must be in \[0, 1\], got 1.5"),
        (lambda c: c.reflectance([0.5, 0.5], [500, 600, 700]), "do not broadcast"),
        (lambda c: c.reflectance(0.5, 500, polarization="x"), "polarization must be s, p or unpolarized"),
    ],
)
def test_bad_input_raises_error_naming_it(call, message):
    with pytest.raises(ss.Error, match=message):
        call(ss.Conductor("Au"))


def test_unknown_material_and_error_is_a_value_error():
    with pytest.raises(ValueError, match="Unobtainium"):
        ss.Conductor("Unobtainium")
    with pytest.raises(ss.Error, match="material must be a path"):
        ss.Conductor(5)
