"""read_rgl and export_rgl (docs/PYTHON.md): the fields of a real RGL file as numpy arrays, with its luminance the
Rec. 709 Y of its rgb table; an exported file read back with the shapes the format prescribes; bad input raises."""

import numpy as np
import pytest

import surfscatter as ss
from conftest import shared


def test_read_real_file():
    d = ss.read_rgl(str(shared("realdata", "rgl", "paper_white_rgb.bsdf")))
    assert d["description"] == "White A4 paper (160 gsm)"
    assert d["rgb"].shape == (1, 8, 3, 32, 32) and d["rgb"].dtype == np.float32
    y = np.tensordot(np.array([0.2126729, 0.7151522, 0.0721750]), np.moveaxis(d["rgb"], 2, 0), axes=1)
    np.testing.assert_allclose(y, d["luminance"], rtol=1e-3, atol=1e-5)
    assert d["jacobian"][0] == 1


def test_export_round_trip(tmp_path):
    model = ss.bsdf("ggx_stats", surface=ss.KCorrelation(sigma=0.08, corr_length=1.5, gamma=3.5), material="Au")
    path = tmp_path / "gold.bsdf"
    with pytest.raises(ss.Error, match="more than tolerance_percent 2"):  # so coarse a file is far off the model
        ss.export_rgl(model, str(path), format="rgl-spectral", theta_i_count=3, sample_resolution=8,
                      ndf_resolution=16, lambda_step_nm=80)
    assert path.exists()  # written all the same
    acc = ss.export_rgl(model, str(path), format="rgl-spectral", theta_i_count=3, sample_resolution=8,
                        ndf_resolution=16, lambda_step_nm=80, tolerance_percent=1e6)
    assert acc["compared"] > 1000 and 0.02 < acc["worst"] < 1e4 and acc["lambda_nm"] in (360, 550, 1000)
    assert acc["jump_band"] == 0 and acc["jump_compared"] == 0  # a lobe without a jump (two_scale's: docs/MODELS.md)
    d = ss.read_rgl(str(path))
    assert d["spectra"].shape == (1, 3, len(d["wavelengths"]), 8, 8)
    assert d["wavelengths"][0] == 360 and d["wavelengths"][-1] == 1000
    assert d["vndf"].shape == (1, 3, 16, 16) and d["ndf"].shape == (2, 16)
    assert np.all(np.isfinite(d["spectra"])) and np.all(d["spectra"] >= 0)


def test_bad_input(tmp_path):
    model = ss.bsdf("ggx_stats", alpha=0.2, material="Au")
    with pytest.raises(ss.Error, match="format must be one of rgl-spectral"):
        ss.export_rgl(model, str(tmp_path / "x.bsdf"), format="exr")
    (tmp_path / "bad.bsdf").write_bytes(b"not a tensor file")
    with pytest.raises(ss.Error, match="not a tensor file"):
        ss.read_rgl(str(tmp_path / "bad.bsdf"))


def test_export_specular_lobe(tmp_path):
    smooth = ss.bsdf("ghs", surface=ss.KCorrelation(sigma=0.02, corr_length=2, gamma=3), material="Au")
    # 8 x 8 samples spread the lobe far beyond its core (measured 1.3e4 times the continuous part there): any tolerance.
    acc = ss.export_rgl(smooth, str(tmp_path / "lobe.bsdf"), theta_i_count=3, sample_resolution=8, ndf_resolution=16,
                        lambda_step_nm=80, tolerance_percent=1e9, specular_lobe_deg=0.5)
    assert acc["compared"] > 0
    rough = ss.bsdf("ggx_stats", surface=ss.KCorrelation(sigma=0.08, corr_length=1.5, gamma=3.5), material="Au")
    with pytest.raises(ss.Error, match="has no coherent specular part"):
        ss.export_rgl(rough, str(tmp_path / "x.bsdf"), theta_i_count=3, sample_resolution=8, ndf_resolution=16,
                      lambda_step_nm=80, specular_lobe_deg=0.5)
