#!/usr/bin/python3
"""In-plane BRDF slices written by `surfscatter brdf slice`: one panel per incidence angle, one curve per model,
log scale; the delta (specular) part is printed in the legend.
Usage: brdf_slice.py slices.csv out.png [title] [name=label ...] (legends show a model's label instead of its name)"""
import csv
import sys
from collections import defaultdict

from plotting import run, save  # this folder: atomic writes, one-line failures
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    path, out = sys.argv[1], sys.argv[2]
    title = sys.argv[3] if len(sys.argv) > 3 else ""
    labels = dict(a.partition("=")[::2] for a in sys.argv[4:])
    data = defaultdict(lambda: ([], []))
    specular = {}
    with open(path) as f:
        for row in csv.DictReader(f):
            key = (float(row["theta_i"]), row["model"])
            data[key][0].append(float(row["theta_o_signed"]))
            data[key][1].append(float(row["brdf"]))
            specular[key] = float(row["specular"])
    thetas = sorted({k[0] for k in data})
    models = list(dict.fromkeys(k[1] for k in data))
    fig, axes = plt.subplots(1, len(thetas), figsize=(4.2 * len(thetas), 3.6), squeeze=False)
    for ax, ti in zip(axes[0], thetas):
        peak = max(max(data[(ti, m)][1]) for m in models)
        for m in models:
            x, y = data[(ti, m)]
            y = [v if v > 0 else float("nan") for v in y]
            name = labels.get(m, m)
            label = name if specular[(ti, m)] == 0 else f"{name} (delta {specular[(ti, m)]:.3g})"
            ax.semilogy(x, y, label=label, lw=1.3)
        ax.axvline(ti, color="0.7", lw=0.8, ls=":")
        ax.set_title(f"theta_i = {ti:g} deg")
        ax.set_xlabel("theta_o (deg, + = specular side)")
        ax.set_xlim(-90, 90)
        ax.set_ylim(peak * 1e-9, peak * 3)  # nine decades below the peak: deeper tails are not visible anyway
        ax.grid(True, which="major", alpha=0.3)
    axes[0][0].set_ylabel("BRDF (1/sr)")
    axes[0][-1].legend()
    if title:
        fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    save(fig, out, dpi=90)


if __name__ == "__main__":
    run(main)
