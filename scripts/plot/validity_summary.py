#!/usr/bin/python3
"""The README's validity figure: every case of scripts/validity-report (OUTDIR/<surface>_<metal>_<nm>_<theta_i>_<pol>
.json) as each model's median relative error against exact-1d (log scale), one panel per surface, the cases along x
(metal, wavelength, incidence, polarisation), with the tolerance and the reference's own standard error.
Usage: validity_summary.py OUTDIR summary.png"""
import glob
import json
import os
import sys

from plotting import PlotError, run, save  # this folder: atomic writes, one-line failures
import matplotlib.pyplot as plt

MODELS = (("ghs", "GHS", "o"), ("ghs_ssa", "SSA", "s"), ("kirchhoff", "Kirchhoff", "^"),
          ("ggx_stats", "GGX (statistics)", "v"), ("two_scale", "two_scale", "D"))
SURFACES = (("rough", "rough KC: sigma 0.15 um, L 4 um, gamma 4"), ("smooth", "smooth KC: sigma 0.02 um, L 2 um, gamma 3"))
METALS = ("Al", "Ag", "Au")


def main():
    if len(sys.argv) != 3:
        raise PlotError("usage: validity_summary.py OUTDIR summary.png")
    cases = {}
    for path in glob.glob(os.path.join(sys.argv[1], "*.json")):
        surface, metal, nm, theta, pol = os.path.basename(path)[:-5].split("_")
        with open(path) as f:
            report = json.load(f)
        cases[(surface, metal, int(nm), int(theta), pol)] = (report["cases"][0], report["criteria"]["tolerance"])
    if not cases:
        raise PlotError(f"{sys.argv[1]}: no finished case (no .json)")
    fig, axes = plt.subplots(2, 1, figsize=(12, 7.5))
    for ax, (surface, title) in zip(axes, SURFACES):
        keys = sorted((k for k in cases if k[0] == surface), key=lambda k: (METALS.index(k[1]), k[2], k[3], k[4]))
        x = range(len(keys))
        for model, label, marker in MODELS:
            y = [100 * cases[k][0]["models"][model]["median_rel_error"] if model in cases[k][0]["models"]
                 else float("nan") for k in keys]
            ax.plot(x, y, marker, ms=4, label=label)
        ax.plot(x, [100 * cases[k][0]["reference_median_rel_stderr"] for k in keys], "k_", ms=8,
                label="reference s.e.")
        if keys:
            ax.axhline(100 * cases[keys[0]][1], color="grey", ls="--", lw=1, label="tolerance")
        ax.set_yscale("log")
        ax.set_ylabel("median relative error (%)")
        ax.set_title(f"{title}: {len(keys)} cases", fontsize=10)
        ax.set_xticks(list(x))
        ax.set_xticklabels([f"{k[1]} {k[2]} {k[3]}{k[4]}" for k in keys], rotation=90, fontsize=6)
        ax.grid(True, which="major", axis="y", alpha=0.3)
    axes[-1].set_xlabel("case: metal, wavelength (nm), theta_i (deg) and polarisation")
    fig.suptitle("1-D models against exact-1d (reference at --target-stderr 2 %): scripts/validity-report",
                 fontsize=11)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="upper center", ncol=7, bbox_to_anchor=(0.5, 0.955), fontsize=8)
    fig.tight_layout(rect=(0, 0, 1, 0.93))
    save(fig, sys.argv[2], dpi=100)


run(main)
