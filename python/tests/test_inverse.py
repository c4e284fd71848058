"""surfscatter.fit_brdf: the same estimates as `surfscatter fit-brdf` on the same data, from a path or from arrays;
bad data raises surfscatter.Error naming the row."""
import csv
import json
import subprocess

import numpy as np
import pytest

import surfscatter as ss
from conftest import CLI, SOURCE_DIR

EXAMPLE = SOURCE_DIR / "examples" / "data" / "fit_brdf_au.csv"


def columns():
    with open(EXAMPLE) as f:
        rows = list(csv.DictReader(f))
    return {key: np.array([float(r[key]) for r in rows]) for key in rows[0]}


def test_fit_brdf_matches_the_cli(tmp_path):
    from_path = ss.fit_brdf(EXAMPLE, "Au", models=["ggx_stats"])
    from_arrays = ss.fit_brdf(columns(), "Au", models=["ggx_stats"])
    out = tmp_path / "fit"
    r = subprocess.run([CLI, "fit-brdf", "--data", str(EXAMPLE), "--material", "Au", "--model", "ggx_stats",
                        "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    cli = json.load(open(f"{out}.json"))
    for got in (from_path, from_arrays):
        fit = got["models"][0]
        assert fit["model"] == "ggx_stats"
        for name in ("sigma_um", "corr_length_um", "gamma"):
            assert fit["parameters"][name]["value"] == pytest.approx(
                cli["models"][0]["parameters"][name]["value"], rel=1e-12)
        assert fit["fitted"].shape == (len(columns()["brdf"]),)
        assert np.all(np.isfinite(fit["residual"]))
        assert got["verdict"] == cli["verdict"]


def test_bad_data_names_the_row():
    data = columns()
    data["brdf"][3] = -1.0
    with pytest.raises(ss.Error, match=r"data row 4: brdf must be finite and >= 0"):
        ss.fit_brdf(data, "Au", models=["ggx_stats"])
    data = columns()
    del data["phi_o_deg"]
    with pytest.raises(ss.Error, match=r"data has no 'phi_o_deg'"):
        ss.fit_brdf(data, "Au", models=["ggx_stats"])
    with pytest.raises(ss.Error, match=r"fix gamma applies to psd kc only"):
        ss.fit_brdf(columns(), "Au", models=["ggx_stats"], psd="gaussian", fix={"gamma": 3.0})


def test_fit_brdf_reads_an_rgl_file(tmp_path):
    model = ss.bsdf("ggx_stats", surface=ss.KCorrelation(sigma=0.1, corr_length=1.5, gamma=3.5), material="Au")
    path = tmp_path / "gold.bsdf"
    ss.export_rgl(model, str(path), theta_i_count=4, sample_resolution=12, ndf_resolution=24, lambda_step_nm=80,
                  tolerance_percent=1e6)
    got = ss.fit_brdf(str(path), "Au", models=["ggx_stats"], wavelengths_nm=[500.0, 600.0])
    assert got["models"][0]["model"] == "ggx_stats"
    assert np.all(np.isfinite(got["models"][0]["residual"]))
    with pytest.raises(ss.Error, match=r"wavelengths_nm applies to RGL .bsdf data only"):
        ss.fit_brdf(columns(), "Au", models=["ggx_stats"], wavelengths_nm=[550.0])


def test_fit_brdf_profile_data():
    """profile='s': in-plane rows, exact-1d's signed angles mapped to phi_o (180 on the specular side). A round trip
    of the format (the 1-D GHS lobe itself, sigma fitted with L and gamma held): an angle mapped to the wrong side
    would move sigma; the accuracy against exact-1d is tests/inverse's FitBrdf.ProfileDataFromExact1d."""
    theta_o = np.array([t for t in np.arange(-60.0, 61.0, 4.0) if abs(t - 30.0) > 3.0])
    surface = ss.KCorrelation(sigma=0.1, corr_length=1.0, gamma=2.5)
    data = {key: [] for key in ("wavelength_nm", "theta_i_deg", "phi_i_deg", "theta_o_deg", "phi_o_deg", "brdf")}
    for wavelength in (600.0, 1000.0):
        lobe = ss.profile_models(surface, "perfect", wavelength, 30.0, "s", theta_o_deg=theta_o, models=["ghs"])
        for t, value in zip(theta_o, lobe["ghs"]["intensity_per_rad"]):
            for key, v in zip(data, (wavelength, 30.0, 0.0, abs(t), 180.0 if t > 0 else 0.0, value)):
                data[key].append(v)
    data = {key: np.array(v) for key, v in data.items()}
    got = ss.fit_brdf(data, "perfect", models=["ghs"], profile="s", fix={"corr_length_um": 1.0, "gamma": 2.5})
    assert got["profile"] == "s"
    assert got["models"][0]["parameters"]["sigma_um"]["value"] == pytest.approx(0.1, rel=1e-3)
    with pytest.raises(ss.Error, match=r"profile must be s or p"):
        ss.fit_brdf(data, "perfect", models=["ghs"], profile="x")
    with pytest.raises(ss.Error, match=r"phi_o_deg must be 0 or 180 for profile data"):
        ss.fit_brdf(columns(), "Au", models=["ghs"], profile="s")
