"""surfscatter.validity: the same table and verdicts as `surfscatter validity` on the same surface and settings."""
import csv
import subprocess

import pytest

import surfscatter as ss
from conftest import CLI, CLI_RTOL, SOURCE_DIR, run_cli


def test_validity_matches_the_cli(tmp_path):
    surface = ss.KCorrelation(0.01, 1.0, 3.0)
    got = ss.validity(surface, "perfect", wavelengths_nm=[550], theta_i_deg=[0], length_um=12, beam_width_um=2,
                      realizations=4, polarisations=["s"])
    # no ggx_stats: gamma 3
    assert [row["model"] for row in got["table"]] == ["ghs", "ghs_ssa", "kirchhoff", "two_scale"]
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
        # the same verdict, its remedy naming each front end's own options
        assert mine["verdict"] == theirs["verdict"].replace("--realizations", "realizations").replace("--bin-deg", "bin_deg")


def test_validity_runs_profiles_until_the_target_standard_error():
    """target_stderr_pct: profiles in rounds until the reference's median standard error over the bins used reaches
    it (a loose 15 % here, to be quick); with realizations it is an error naming both."""
    surface = ss.KCorrelation(0.01, 1.0, 3.0)
    got = ss.validity(surface, "perfect", wavelengths_nm=[550], theta_i_deg=[0], length_um=12, beam_width_um=2,
                      polarisations=["s"], bin_deg=10, target_stderr_pct=15, max_realizations=200)
    verdict = got["verdicts"][0]
    assert verdict["target_reached"]
    assert verdict["reference_median_rel_stderr"] <= 0.15
    assert 16 <= verdict["realizations"] <= 200
    assert verdict["not_compared"] and verdict["not_compared"][0].startswith("ggx_stats: ")  # gamma 3
    with pytest.raises(ss.Error, match="realizations and target_stderr_pct: give one"):
        ss.validity(surface, "perfect", [550], [0], 12, 2, realizations=4, target_stderr_pct=5)
    with pytest.raises(ss.Error, match="max_realizations caps target_stderr_pct's profiles"):
        ss.validity(surface, "perfect", [550], [0], 12, 2, realizations=4, max_realizations=9)


def test_validity_refuses_bad_input():
    with pytest.raises(ss.Error, match="theta_i must be in"):
        ss.validity(ss.KCorrelation(0.01, 1.0, 3.0), "perfect", [550], [90], 12, 2, 4)
    with pytest.raises(ss.Error, match="polarisations"):
        ss.validity(ss.KCorrelation(0.01, 1.0, 3.0), "perfect", [550], [0], 12, 2, 4, polarisations=["x"])


def test_validity_map_matches_the_cli(tmp_path):
    """The map route on the example KC map: the same rows and verdicts as `surfscatter validity --surface-file`."""
    surface_file = SOURCE_DIR / "examples" / "data" / "kc_surface.gsf"
    got = ss.validity_map(str(surface_file), "perfect", wavelengths_nm=[550], theta_i_deg=[0], bin_deg=12)
    assert [row["model"] for row in got["table"]][:2] == ["ghs/measured", "ghs_ssa/measured"]
    verdict = got["verdicts"][0]
    assert verdict["reference_validity"]["valid"]
    assert "ghs_ssa/measured" in verdict["ruled_out"]
    out = tmp_path / "m"
    run_cli("validity", "--surface-file", surface_file, "--material", "perfect", "--wavelengths", "550",
            "--theta-i", "0", "--bin-deg", "12", "-o", out)
    with open(f"{out}.csv") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == len(got["table"])
    for mine, theirs in zip(got["table"], rows):
        assert mine["model"] == theirs["model"]
        assert mine["median_rel_error"] == pytest.approx(float(theirs["median_rel_error"]), rel=CLI_RTOL)
        assert mine["model_energy"] == pytest.approx(float(theirs["model_energy"]), rel=CLI_RTOL)
        assert mine["reference_valid"] == (theirs["reference_valid"] == "1")
        assert mine["verdict"] == theirs["verdict"]


def test_validity_map_synthesises_elliptical_maps():
    """An elliptical KC surface: the maps are drawn with its lay; two_scale takes elliptical statistics too."""
    surface = ss.KCorrelation(0.02, 2.0, 3.0, corr_length_v=4.0, lay_angle_deg=30)
    got = ss.validity_map(surface, "perfect", wavelengths_nm=[550], theta_i_deg=[20], phi_i_deg=[0, 90],
                          map_size_um=32, map_pixels=256, realizations=2, subarea_um=8, bin_deg=6)
    assert {row["phi_i_deg"] for row in got["table"]} == {0, 90}
    assert not any(why.startswith("two_scale: ") for why in got["refused_models"])
    assert "two_scale" in {row["model"] for row in got["table"]}
    assert "corr_length_v 4 um, lay_angle 30 deg" in got["surface"]


def test_validity_map_refuses_bad_input():
    with pytest.raises(ss.Error, match="a height map is one realization"):
        ss.validity_map(str(SOURCE_DIR / "examples" / "data" / "kc_surface.gsf"), "perfect", [550], [0],
                        realizations=2)
    with pytest.raises(ss.Error, match="map_size_um: give the side"):
        ss.validity_map(ss.KCorrelation(0.02, 2.0, 3.0), "perfect", [550], [0])
    with pytest.raises(ss.Error, match="surface must be"):
        ss.validity_map(3, "perfect", [550], [0])


def test_outliers_of_a_map_are_found_filled_and_decide_the_map_route():
    """Eight spikes of 0.1 um on a smooth synthesised map: HeightMap.outliers() finds them, fill_outliers() removes
    them, and validity_map refuses the map with outliers='keep' (they dominate) and runs with 'fill'."""
    clean = ss.synthesize(ss.KCorrelation(0.005, 2.0, 3.0), size=128, spacing_um=0.5, seed=7)
    h = clean.heights_um.copy()
    for k in range(8):
        h[9 + 13 * k, 7 + 14 * k] += 0.1 if k % 2 else -0.1
    spiked = ss.HeightMap(h, 0.5, origin="spiked")
    found = spiked.outliers()
    assert found["points"] == 8 and found["spots"] == 8 and found["dominant"]
    assert spiked.fill_outliers().outliers()["points"] == 0
    assert clean.outliers()["points"] == 0
    with pytest.raises(ss.Error, match="nothing can be trusted: .*8 points in 8 spots"):
        ss.validity_map(spiked, "perfect", [550], [0], bin_deg=6)
    got = ss.validity_map(spiked, "perfect", [550], [0], bin_deg=6, outliers="fill")
    assert got["outliers"]["policy"] == "fill" and got["outliers"]["points"] == 8
    with pytest.raises(ss.Error, match="outliers must be keep or fill"):
        ss.validity_map(spiked, "perfect", [550], [0], outliers="drop")
    with pytest.raises(ss.Error, match="outliers prepares a measured map"):
        ss.validity_map(ss.KCorrelation(0.02, 2.0, 3.0), "perfect", [550], [0], map_size_um=16, outliers="fill")
