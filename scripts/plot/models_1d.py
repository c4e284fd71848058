#!/usr/bin/python3
"""The 1-D models written by `surfscatter reference models-1d`, per radian on a log scale, optionally with the
incoherent part of `surfscatter reference exact-1d`'s statistical mode and its Monte Carlo standard error.
Usage: models_1d.py models.csv models.json out.png [title] [exact.csv]"""
import csv
import json
import re
import sys

from plotting import PlotError, run, save, wrap  # this folder: atomic writes, one-line failures
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def columns(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {key: [float(r[key]) for r in rows] for key in rows[0]}


def surface_text(meta):
    """The surface under the title, from the JSON's statistics key: kc(L=2,gamma=3) or gauss(l=2), and sigma_h."""
    key = meta["surface"]
    numbers = {name: float(value) for name, value in re.findall(r"(\w+)=([^,)]+)", key)}
    if key.startswith("kc(") and {"L", "gamma"} <= numbers.keys():
        shape = f"KC, L {numbers['L']:.4g} um, gamma {numbers['gamma']:.4g}"
    elif key.startswith("gauss(") and "l" in numbers:
        shape = f"Gaussian ACV, l {numbers['l']:.4g} um"
    else:
        shape = key
    return f"surface: {shape}, sigma_h {meta['sigma_h_um']:.4g} um"


def main():
    models_path, json_path, out = sys.argv[1], sys.argv[2], sys.argv[3]
    title = sys.argv[4] if len(sys.argv) > 4 else ""
    exact_path = sys.argv[5] if len(sys.argv) > 5 else None
    data = columns(models_path)
    meta = json.load(open(json_path))
    theta = data["theta_o_deg"]
    fig, ax = plt.subplots(figsize=(7, 4.2))
    peak = 0.0
    if exact_path:
        exact = columns(exact_path)
        if exact["theta_o_deg"] != theta:
            raise PlotError(f"{exact_path} is not on the theta_o grid of {models_path}")
        y, e = exact["incoherent_per_rad"], exact["incoherent_stderr_per_rad"]
        ax.fill_between(theta, [max(a - b, 1e-30) for a, b in zip(y, e)], [a + b for a, b in zip(y, e)],
                        color="0.8", label="exact-1d +- standard error")
        ax.semilogy(theta, [v if v > 0 else float("nan") for v in y], color="k", lw=1.0, label="exact-1d (incoherent)")
        peak = max(y)
    for key, values in data.items():
        if key == "theta_o_deg":
            continue
        name = key.removesuffix("_per_rad")
        coherent = meta["models"][name]["coherent"]
        ax.semilogy(theta, [v if v > 0 else float("nan") for v in values], lw=1.3,
                    label=f"{name} (coherent {coherent:.3g})")
        peak = max(peak, max(values))
    ax.axvline(meta["theta_i_deg"], color="0.6", lw=0.8, ls=":")
    ax.set_xlim(-90, 90)
    ax.set_ylim(peak * 1e-6, peak * 3)
    ax.set_xlabel("theta_o (deg, + = specular side)")
    ax.set_ylabel("incoherent intensity (1/rad)")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend()
    heading = "\n".join(filter(None, [title, surface_text(meta)]))
    ax.set_title(wrap(heading, 0.9 * fig.get_figwidth(), 10), fontsize=10)
    fig.tight_layout()
    save(fig, out, dpi=90)


if __name__ == "__main__":
    run(main)
