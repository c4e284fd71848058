#!/usr/bin/python3
"""The Kirchhoff BRDF written by `surfscatter reference kirchhoff`: left, log10 BRDF over the outgoing direction
cosines (o_x, o_y) on the sub-areas' lattice; right, the in-plane slice (lattice directions within half a step of
the plane of incidence) with its standard error and coherent part.
Usage: kirchhoff_map.py out.csv out.png theta_i_deg phi_i_deg step_x step_y title"""
import csv
import math
import sys

from plotting import run, save  # this folder: atomic writes, one-line failures
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main():
    path, out = sys.argv[1], sys.argv[2]
    theta_i, phi_i = math.radians(float(sys.argv[3])), math.radians(float(sys.argv[4]))
    step_x, step_y, title = float(sys.argv[5]), float(sys.argv[6]), sys.argv[7]
    with open(path) as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    theta = np.radians([r["theta_o_deg"] for r in rows])
    phi = np.radians([r["phi_o_deg"] for r in rows])
    brdf = np.array([r["brdf_per_sr"] for r in rows])
    error = np.array([r["standard_error_per_sr"] for r in rows])
    coherent = np.array([r["coherent_per_sr"] for r in rows])
    ox, oy = np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi)
    ix, iy = math.sin(theta_i) * math.cos(phi_i), math.sin(theta_i) * math.sin(phi_i)
    mx = np.rint((ox + ix) / step_x).astype(int)
    my = np.rint((oy + iy) / step_y).astype(int)
    image = np.full((my.max() - my.min() + 1, mx.max() - mx.min() + 1), np.nan)
    peak = brdf.max()
    image[my - my.min(), mx - mx.min()] = np.log10(np.maximum(brdf, peak * 1e-8))
    extent = [(mx.min() - 0.5) * step_x - ix, (mx.max() + 0.5) * step_x - ix,
              (my.min() - 0.5) * step_y - iy, (my.max() + 0.5) * step_y - iy]
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.2))
    shown = left.imshow(image, origin="lower", extent=extent, cmap="magma")
    left.add_patch(plt.Circle((0, 0), 1, fill=False, color="0.6", lw=0.8))
    left.set_xlabel("o_x")
    left.set_ylabel("o_y")
    left.set_aspect("equal")
    fig.colorbar(shown, ax=left, label="log10 BRDF (1/sr)")
    along = ox * math.cos(phi_i) + oy * math.sin(phi_i)
    across = -ox * math.sin(phi_i) + oy * math.cos(phi_i)
    keep = np.abs(across) <= 0.5 * max(step_x, step_y)
    signed = np.degrees(np.arcsin(np.clip(-along[keep], -1, 1)))
    order = np.argsort(signed)
    s, b, e, c = signed[order], brdf[keep][order], error[keep][order], coherent[keep][order]
    right.semilogy(s, b, lw=1.2, label="BRDF")
    right.fill_between(s, np.maximum(b - e, peak * 1e-9), b + e, alpha=0.3, label="standard error")
    right.semilogy(s, np.where(c > 0, c, np.nan), "--", lw=0.9, label="coherent part")
    right.axvline(math.degrees(theta_i), color="0.7", lw=0.8, ls=":")
    right.set_ylim(peak * 1e-8, peak * 3)
    right.set_xlabel("theta_o in the plane of incidence (deg, + = specular side)")
    right.set_ylabel("BRDF (1/sr)")
    right.legend()
    right.grid(True, alpha=0.3)
    fig.suptitle(f"Kirchhoff on the map: theta_i = {math.degrees(theta_i):g} deg, {title}", fontsize=10)
    fig.tight_layout()
    save(fig, out, dpi=90)


if __name__ == "__main__":
    run(main)
