"""surfscatter.profile_models: the 1-D models against `surfscatter reference models-1d` on the same surface, the
energy of GHS for a perfect conductor, and options no chosen model uses refused."""

import csv
import json

import numpy as np
import pytest

import surfscatter as ss
from conftest import CLI_RTOL, run_cli


def test_matches_the_cli(tmp_path):
    out = tmp_path / "models.csv"
    run_cli("reference", "models-1d", "--psd", "kc", "--sigma", 0.04, "--corr-length", 1.5, "--gamma", 3,
            "--material", "Au", "--wavelength", 633, "--theta-i", 40, "--polarisation", "p", "--fresnel", "half",
            "-o", out)
    with open(out) as f:
        rows = list(csv.DictReader(f))
    meta = json.loads(out.with_suffix(".json").read_text())
    got = ss.profile_models(ss.KCorrelation(0.04, 1.5, 3.0), "Au", wavelength_nm=633, theta_i_deg=40,
                            polarisation="p", fresnel="half")
    np.testing.assert_allclose(got["theta_o_deg"], [float(r["theta_o_deg"]) for r in rows], rtol=0, atol=1e-9)
    for name in ("ghs", "ghs_ssa", "kirchhoff"):
        cli = np.array([float(r[f"{name}_per_rad"]) for r in rows])
        np.testing.assert_allclose(got[name]["intensity_per_rad"], cli, rtol=CLI_RTOL, atol=1e-300)
        assert got[name]["coherent"] == pytest.approx(meta["models"][name]["coherent"], rel=CLI_RTOL)


def test_ghs_conserves_energy_on_a_perfect_conductor():
    theta = np.linspace(-90, 90, 3601)
    got = ss.profile_models(ss.GaussianAcv(0.1, 2.0), "perfect", wavelength_nm=550, theta_i_deg=20,
                            polarisation="s", theta_o_deg=theta, models=["ghs"])
    lobe = np.trapz(got["ghs"]["intensity_per_rad"], np.radians(theta))
    assert got["ghs"]["coherent"] + lobe == pytest.approx(1.0, abs=1e-6)


def test_refuses_options_no_model_uses():
    with pytest.raises(ss.Error, match="ssa_form is used by ghs_ssa only"):
        ss.profile_models(ss.GaussianAcv(0.1, 2.0), "perfect", 550, 20, "s", models=["ghs"], ssa_form="strict")
    with pytest.raises(ss.Error, match="polarisation must be s or p, got 'x'"):
        ss.profile_models(ss.GaussianAcv(0.1, 2.0), "perfect", 550, 20, "x")
    with pytest.raises(ss.Error, match=r"theta_i must be in \[0, 90\) degrees, got 90"):
        ss.profile_models(ss.GaussianAcv(0.1, 2.0), "perfect", 550, 90, "s")
