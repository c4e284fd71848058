#!/usr/bin/python3
"""The plots of `surfscatter validity`'s map route: slices of each model against the Kirchhoff reference of the
map(s) in the plane of incidence (the lattice bins within half a bin of it, diffuse parts per steradian, the
reference's standard error as a band), one panel per case, titled with whether Kirchhoff is valid there; and each
model's median relative error over theta_i and theta_o (the bins the comparison used, in 5 degree rings of theta_o),
one panel per model and (wavelength, phi_i).
Usage: validity_map.py OUT.json slices.png error_map.png"""
import math

from plotting import run  # this folder: one-line failures
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from validity import finish_error_map, finish_slices, plot_report, positive  # noqa: E402  (the profiles route's plots, same directory)

RING_DEG = 5.0


def in_plane(case, bin_deg):
    """Indices of the bins near the plane of incidence, sorted by signed theta_o (forward scattering positive)."""
    b = case["binned"]
    phi = math.radians(case["phi_i_deg"])
    ox, oy = np.array(b["o_x"]), np.array(b["o_y"])
    along = -(ox * math.cos(phi) + oy * math.sin(phi))  # towards the specular side
    across = -ox * math.sin(phi) + oy * math.cos(phi)
    half_bin = 0.5 * max(math.radians(bin_deg), max(case["lattice_step"]))
    keep = np.nonzero(np.abs(across) <= half_bin)[0]
    theta = np.degrees(np.arcsin(np.clip(along[keep], -1, 1)))
    order = np.argsort(theta)
    return keep[order], theta[order]


def slices(report, out):
    cases = report["cases"]
    cols = min(len(cases), 3)
    rows = math.ceil(len(cases) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.4 * cols, 3.1 * rows), squeeze=False)
    for ax, case in zip(axes.flat, cases):
        idx, theta = in_plane(case, report["criteria"]["bin_deg"])
        b = case["binned"]
        y = np.array(b["reference_per_sr"])[idx]
        e = np.array(b["reference_stderr_per_sr"])[idx]
        ax.fill_between(theta, np.maximum(y - e, 1e-30), y + e, color="0.8", label="Kirchhoff +- s.e.")
        ax.semilogy(theta, positive(y), color="k", lw=1.0, label="Kirchhoff (map)")
        for name, m in case["models"].items():
            ax.semilogy(theta, positive(np.array(b["models"][name])[idx]), lw=1.0,
                        label=f"{name} ({100 * m['median_rel_error']:.3g} %)")
        peak = max(np.nanmax(y) if y.size else 0, 1e-30)
        ax.set_ylim(peak * 1e-3, peak * 3)
        ax.set_xlim(-90, 90)
        valid = "Kirchhoff valid" if case["reference_validity"]["valid"] else "Kirchhoff NOT valid"
        ax.set_title(f"{case['wavelength_nm']:g} nm, theta_i {case['theta_i_deg']:g}, phi_i {case['phi_i_deg']:g}"
                     f" deg: {valid}", fontsize=7)
        ax.tick_params(labelsize=7)
        ax.legend()
    finish_slices(fig, axes, len(cases), "theta_o in the plane of incidence (deg, specular side positive)",
                  "diffuse BRDF (1/sr)", report, out)


def error_map(report, out):
    cases = report["cases"]
    models = list(cases[0]["models"])
    groups = sorted({(c["wavelength_nm"], c["phi_i_deg"]) for c in cases})
    theta_i = sorted({c["theta_i_deg"] for c in cases})
    rings = np.arange(0.0, 90.0 + RING_DEG, RING_DEG)
    fig, axes = plt.subplots(len(models), len(groups), figsize=(3.3 * len(groups), 1.9 * len(models)),
                             squeeze=False)
    image = None
    for col, (wavelength, phi_i) in enumerate(groups):
        for row, name in enumerate(models):
            grid = np.full((len(theta_i), len(rings) - 1), np.nan)
            for c in cases:
                if (c["wavelength_nm"], c["phi_i_deg"]) != (wavelength, phi_i):
                    continue
                ref = np.array(c["binned"]["reference_per_sr"])
                model = np.array(c["binned"]["models"][name])
                used = np.array(c["models"][name]["used_bins"], dtype=int)
                if not used.size:
                    continue
                err = np.abs(model[used] - ref[used]) / ref[used]
                ring = np.digitize(np.array(c["binned"]["theta_o_deg"])[used], rings) - 1
                for r in np.unique(ring):
                    grid[theta_i.index(c["theta_i_deg"]), r] = np.median(err[ring == r])
            ax = axes[row][col]
            edges_i = np.array(theta_i + [theta_i[-1] + (theta_i[-1] - theta_i[0]) / max(len(theta_i) - 1, 1)
                                          if len(theta_i) > 1 else theta_i[0] + 10])
            image = ax.pcolormesh(rings, edges_i, 100 * grid, cmap="magma_r", vmin=0, vmax=50, shading="flat")
            ax.set_title(f"{name}: {wavelength:g} nm, phi_i {phi_i:g}", fontsize=7)
            ax.set_xlim(0, 90)
            ax.set_yticks(theta_i)
            ax.tick_params(labelsize=7)
    finish_error_map(fig, axes, image, "theta_o (deg, any azimuth)", "median relative error (%)", out)


if __name__ == "__main__":
    run(plot_report, slices, error_map)
