#!/usr/bin/python3
"""Directional albedo against the incidence angle, one curve per model, from the CSV a study's albedo jobs write
(model,theta_i,albedo,scatter,specular,phi_i_deg). A model tabulated at several incidence azimuths (an anisotropic
one) is drawn as its azimuthal mean with the band from its lowest to its highest albedo over the azimuths.
Usage: albedo_curves.py albedo.csv out.png [title] [name=label ...] (legends show a model's label instead of its name)"""
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
    # model -> theta_i -> [(albedo, specular) per azimuth]; CSVs from before phi_i_deg have one azimuth
    rows = defaultdict(lambda: defaultdict(list))
    azimuths = defaultdict(set)
    with open(path) as f:
        for row in csv.DictReader(f):
            rows[row["model"]][float(row["theta_i"])].append((float(row["albedo"]), float(row["specular"])))
            azimuths[row["model"]].add(row.get("phi_i_deg", "0"))
    fig, ax = plt.subplots(figsize=(5.6, 3.8))
    for name, by_theta in rows.items():
        theta = sorted(by_theta)
        total = [[a for a, _ in by_theta[t]] for t in theta]
        specular = [sum(s for _, s in by_theta[t]) / len(by_theta[t]) for t in theta]
        model = labels.get(name, name)
        mean = [sum(a) / len(a) for a in total]
        several = len(azimuths[name]) > 1
        label = f"{model} (mean over {len(azimuths[name])} phi_i, band min..max)" if several else model
        line = ax.plot(theta, mean, marker="o", ms=3, lw=1.3, label=label)[0]
        if several:
            ax.fill_between(theta, [min(a) for a in total], [max(a) for a in total], color=line.get_color(), alpha=0.25,
                            lw=0)
        if any(s > 0 for s in specular):
            ax.plot(theta, specular, ls=":", lw=1.0, color=line.get_color(), label=f"{model} (delta part)")
    ax.set_xlabel("theta_i (deg)")
    ax.set_ylabel("directional albedo")
    ax.set_xlim(0, 90)
    ax.grid(True, alpha=0.3)
    ax.legend()
    if title:
        ax.set_title(title, fontsize=10)
    fig.tight_layout()
    save(fig, out, dpi=90)


if __name__ == "__main__":
    run(main)
