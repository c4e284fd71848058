#!/usr/bin/python3
"""Directional albedo against the incidence angle, one curve per model, from the CSV a study's albedo jobs write
(model,theta_i,albedo,scatter,specular).
Usage: albedo_curves.py albedo.csv out.png [title] [name=label ...] (legends show a model's label instead of its name)"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    path, out = sys.argv[1], sys.argv[2]
    title = sys.argv[3] if len(sys.argv) > 3 else ""
    labels = dict(a.partition("=")[::2] for a in sys.argv[4:])
    curves = defaultdict(lambda: ([], [], []))
    with open(path) as f:
        for row in csv.DictReader(f):
            theta, total, specular = curves[row["model"]]
            theta.append(float(row["theta_i"]))
            total.append(float(row["albedo"]))
            specular.append(float(row["specular"]))
    fig, ax = plt.subplots(figsize=(5.6, 3.8))
    for name, (theta, total, specular) in curves.items():
        model = labels.get(name, name)
        line = ax.plot(theta, total, marker="o", ms=3, lw=1.3, label=model)[0]
        if any(s > 0 for s in specular):
            ax.plot(theta, specular, ls=":", lw=1.0, color=line.get_color(), label=f"{model} (delta part)")
    ax.set_xlabel("theta_i (deg)")
    ax.set_ylabel("directional albedo")
    ax.set_xlim(0, 90)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    if title:
        ax.set_title(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=90)


if __name__ == "__main__":
    main()
