#!/usr/bin/python3
"""The plots of `surfscatter validity`: slices of each model against the exact reference (incoherent part, with its
Monte Carlo standard error as a band), one panel per case, and the relative model error over theta_i and theta_o
(theta_o bins the comparison used only), one panel per model and (wavelength, polarisation).
Usage: validity.py OUT.json slices.png error_map.png"""
import json
import math
import sys

from plotting import run, save  # this folder: atomic writes, one-line failures
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def positive(values):
    return [v if v > 0 else float("nan") for v in values]


def slices(report, out):
    cases = report["cases"]
    cols = min(len(cases), 3)
    rows = math.ceil(len(cases) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.0 * rows), squeeze=False)
    for ax, case in zip(axes.flat, cases):
        theta = case["theta_o_deg"]
        y = np.array(case["reference_incoherent_per_rad"])
        e = np.array(case["reference_incoherent_stderr_per_rad"])
        ax.fill_between(theta, np.maximum(y - e, 1e-30), y + e, color="0.8", label="exact +- s.e.")
        ax.semilogy(theta, positive(y), color="k", lw=1.0, label="exact-1d")
        for name, m in case["models"].items():
            ax.semilogy(theta, positive(m["incoherent_per_rad"]), lw=1.1,
                        label=f"{name} ({100 * m['median_rel_error']:.3g} %)")
        peak = max(y.max(), 1e-30)
        ax.set_ylim(peak * 1e-3, peak * 3)
        ax.set_xlim(-90, 90)
        ax.set_title(f"{case['wavelength_nm']:g} nm, {case['theta_i_deg']:g} deg, {case['polarisation']}", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.legend()
    finish_slices(fig, axes, len(cases), "theta_o (deg)", "incoherent intensity (1/rad)", report, out)


def finish_slices(fig, axes, panels, xlabel, ylabel, report, out):
    """Blank unused panels, labels, the title and the file of a slices figure (this script's and validity_map.py's)."""
    for ax in list(axes.flat)[panels:]:
        ax.axis("off")
    fig.supxlabel(xlabel, fontsize=9)
    fig.supylabel(ylabel, fontsize=9)
    fig.suptitle(f"{report['surface']}, {report['material']}", fontsize=10)
    fig.tight_layout(rect=(0.02, 0.03, 1, 1))  # room for the figure's axis labels beside the panels' ticks
    save(fig, out, dpi=80)


def error_map(report, out):
    cases = report["cases"]
    models = list(cases[0]["models"])
    groups = sorted({(c["wavelength_nm"], c["polarisation"]) for c in cases})
    theta_i = sorted({c["theta_i_deg"] for c in cases})
    theta_o = np.array(cases[0]["binned"]["theta_o_deg"])
    fig, axes = plt.subplots(len(models), len(groups), figsize=(3.3 * len(groups), 2.2 * len(models)),
                             squeeze=False)
    image = None
    for col, (wavelength, polarisation) in enumerate(groups):
        for row, name in enumerate(models):
            grid = np.full((len(theta_i), len(theta_o)), np.nan)
            for c in cases:
                if (c["wavelength_nm"], c["polarisation"]) != (wavelength, polarisation):
                    continue
                ref = np.array(c["binned"]["reference_per_rad"])
                model = np.array(c["binned"]["models"][name])
                used = np.array(c["models"][name]["used_bins"], dtype=int)
                if used.size:
                    grid[theta_i.index(c["theta_i_deg"]), used] = np.abs(model[used] - ref[used]) / ref[used]
            ax = axes[row][col]
            edges_i = np.array(theta_i + [theta_i[-1] + (theta_i[-1] - theta_i[0]) / max(len(theta_i) - 1, 1)
                                          if len(theta_i) > 1 else theta_i[0] + 10])
            edges_o = np.concatenate(([-90.0], 0.5 * (theta_o[1:] + theta_o[:-1]), [90.0]))
            image = ax.pcolormesh(edges_o, edges_i, 100 * grid, cmap="magma_r", vmin=0, vmax=50, shading="flat")
            ax.set_title(f"{name}: {wavelength:g} nm, {polarisation}", fontsize=8)
            ax.set_xlim(-90, 90)
            ax.set_yticks(theta_i)
            ax.tick_params(labelsize=7)
    finish_error_map(fig, axes, image, "theta_o (deg)", "relative error (%)", out)


def finish_error_map(fig, axes, image, xlabel, colour_label, out):
    """Labels, the colour bar and the file of an error map (this script's and validity_map.py's)."""
    fig.supxlabel(xlabel, fontsize=9)
    fig.supylabel("theta_i (deg, rows)", fontsize=9)
    fig.tight_layout(rect=(0.02, 0.03, 1, 1))  # room for the figure's axis labels beside the panels' ticks
    # Clipped at 50 % (an arrow: larger errors are drawn black); white bins are those the comparison did not use.
    bar = fig.colorbar(image, ax=axes, shrink=0.8, extend="max")
    bar.set_label(f"{colour_label}, |model - exact| / exact\n(black: 50 % or more; white: bin not compared)", fontsize=9)
    save(fig, out, dpi=80)


def plot_report(slices_plot, error_map_plot):
    """Usage: script OUT.json slices.png error_map.png"""
    report = json.load(open(sys.argv[1]))
    slices_plot(report, sys.argv[2])
    error_map_plot(report, sys.argv[3])


if __name__ == "__main__":
    run(plot_report, slices, error_map)
