"""surfscatter.validity: the same table and verdicts as `surfscatter validity` on the same surface and settings."""
import csv
import subprocess

import pytest

import surfscatter as ss
from conftest import CLI, CLI_RTOL


def test_validity_matches_the_cli(tmp_path):
    surface = ss.KCorrelation(0.01, 1.0, 3.0)
    got = ss.validity(surface, "perfect", wavelengths_nm=[550], theta_i_deg=[0], length_um=12, beam_width_um=2,
                      realizations=4, polarisations=["s"])
    assert [row["model"] for row in got["table"]] == ["ghs", "ghs_ssa", "kirchhoff"]
    assert len(got["verdicts"]) == 1 and not got["verdicts"][0]["conclusive"]
    out = tmp_path / "v"
    r = subprocess.run([CLI, "validity", "--psd", "kc", "--sigma", "0.01", "--corr-length", "1", "--gamma", "3",
                        "--material", "perfect", "--wavelengths", "550", "--theta-i", "0", "--polarisation", "s",
                        "--length-um", "12", "--beam-width", "2", "--realizations", "4", "-o", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 2, r.stderr  # 4 realizations: nothing can be concluded
    with open(f"{out}.csv") as f:
        rows = list(csv.DictReader(f))
    for mine, theirs in zip(got["table"], rows):
        assert mine["model"] == theirs["model"]
        assert mine["median_rel_error"] == pytest.approx(float(theirs["median_rel_error"]), rel=CLI_RTOL)
        assert mine["directions_used"] == int(theirs["directions_used"])
        assert mine["verdict"] == theirs["verdict"]


def test_validity_refuses_bad_input():
    with pytest.raises(ss.Error, match="theta_i must be in"):
        ss.validity(ss.KCorrelation(0.01, 1.0, 3.0), "perfect", [550], [90], 12, 2, 4)
    with pytest.raises(ss.Error, match="polarisations"):
        ss.validity(ss.KCorrelation(0.01, 1.0, 3.0), "perfect", [550], [0], 12, 2, 4, polarisations=["x"])
