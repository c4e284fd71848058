"""Normal-incidence reflectance of metals and their colour swatches (written by `surfscatter metals`).

usage: metals.py <metals_reflectance.csv> <metals_swatches.json> <reflectance.png> <swatches.png>
The CSV has a column wavelength_nm and one column of R per metal; the JSON lists per metal the 8-bit sRGB colour
white-balanced to the lamp (srgb8) and as lit (srgb8_as_lit), see `surfscatter metals --help`.
"""
import json
import sys

from plotting import run, save  # this folder: atomic writes, one-line failures
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def plot_reflectance(csv_path, png_path):
    data = np.genfromtxt(csv_path, delimiter=",", names=True)
    names = [n for n in data.dtype.names if n != "wavelength_nm"]
    fig, ax = plt.subplots(figsize=(8, 5))
    styles = ["-", "--", "-.", ":"]
    for i, name in enumerate(names):
        ax.plot(data["wavelength_nm"], data[name], styles[i // 10 % 4], color=f"C{i % 10}", lw=1.6, label=name)
    ax.set_xlabel("wavelength [nm]")
    ax.set_ylabel("reflectance at normal incidence")
    ax.set_xlim(data["wavelength_nm"][0], data["wavelength_nm"][-1])
    ax.set_ylim(0, 1)
    ax.grid(True, alpha=0.3)
    ax.legend(ncol=2, fontsize=9, loc="lower right")
    ax.set_title("Metals, Lorentz-Drude model (Rakic et al. 1998): R = |(N-1)/(N+1)|$^2$", fontsize=10)
    fig.tight_layout()
    save(fig, png_path, dpi=120)


def plot_swatches(json_path, png_path):
    with open(json_path) as f:
        info = json.load(f)
    metals = info["metals"]
    fig, ax = plt.subplots(figsize=(1.1 * len(metals) + 1.6, 3.4))
    for i, m in enumerate(metals):
        for row, key in enumerate(["srgb8", "srgb8_as_lit"]):
            colour = np.array(m[key]) / 255.0
            ax.add_patch(plt.Rectangle((i + 0.05, 1 - row + 0.05), 0.9, 0.9, color=colour))
            ax.text(i + 0.5, 1 - row + 0.5, " ".join(str(c) for c in m[key]), ha="center", va="center",
                    fontsize=6, color="black" if colour.mean() > 0.45 else "white")
        ax.text(i + 0.5, 2.1, m["metal"], ha="center", va="bottom", fontsize=10)
    ax.text(-0.08, 1.5, "white-\nbalanced", ha="right", va="center", fontsize=8)
    ax.text(-0.08, 0.5, "as lit", ha="right", va="center", fontsize=8)
    ax.set_xlim(-1.2, len(metals))
    ax.set_ylim(0, 2.5)
    ax.set_aspect("equal")
    ax.axis("off")
    ax.set_title(f"Specular colour at normal incidence under a {info['illuminant']} lamp (sRGB)", fontsize=10)
    fig.tight_layout()
    save(fig, png_path, dpi=150, facecolor="0.5")


def main():
    if len(sys.argv) != 5:
        sys.exit("usage: metals.py <metals_reflectance.csv> <metals_swatches.json> <reflectance.png> <swatches.png>")
    plot_reflectance(sys.argv[1], sys.argv[3])
    plot_swatches(sys.argv[2], sys.argv[4])


if __name__ == "__main__":
    run(main)
