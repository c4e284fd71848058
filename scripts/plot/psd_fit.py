"""Radial PSD of a height map with its KC fit (`surfscatter surface fit --plot`) or with the PSD the measured route
uses (`surfscatter surface info --plot`), and the 2-D PSD beside it.

usage: psd_fit.py <psd.csv> <out.png> [title [<psd2d.npy> <zeta_x_left> <zeta_x_right> <zeta_y_bottom> <zeta_y_top>]]
The CSV has columns zeta (rad/um), psd (um^4), count, kc_fit or model_psd (um^4), in_band (1 if the ring was used),
independent_samples (of each ring: its mean's relative standard error is 1/sqrt of it, drawn as a band), and for a
profile (`surface info | fit` on a line scan) a column `profile`: the rings are bands of its 1-D PSD (um^3), and
`surface info`'s model_psd column (the PSD itself) is not drawn.
Rings whose periods exceed a third of the map (zeta < 3 dzeta) are shaded: few samples hold them.
The .npy holds the 2-D PSD (um^4) over the zeta-plane, centred, rows = zeta_y; the four numbers are its outer
edges (rad/um). A directional texture shows as a streak through the origin, perpendicular to the lay.
"""
import sys

from plotting import run, save, wrap  # this folder: atomic writes, one-line failures
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def radial_panels(fig, spec, data, title):
    names = data.dtype.names
    measured = "model_psd" in names
    profile = "profile" in names
    noun, unit = ("1-D PSD", "3") if profile else ("radial PSD", "4")
    zeta, psd, band = data["zeta"], data["psd"], data["in_band"] > 0.5
    fit = data["model_psd" if measured else "kc_fit"]
    ax = fig.add_subplot(spec[0, 0])
    ax_res = fig.add_subplot(spec[1, 0], sharex=ax)
    ring_width = np.median(np.diff(zeta))
    for a in (ax, ax_res):
        a.axvspan(zeta[0] * 0.8, 3.0 * ring_width, color="0.92", zorder=0)
    if "independent_samples" in names:
        error = 1.0 / np.sqrt(np.maximum(data["independent_samples"], 1e-12))
        ax.fill_between(zeta, psd * np.exp(-error), psd * np.exp(error), color="C0", alpha=0.15, lw=0,
                        label="+-1 standard error")
    ax.loglog(zeta[~band], psd[~band], ".", color="0.6", ms=3, label=f"{noun} (not fitted)")
    ax.loglog(zeta[band], psd[band], ".", color="C0", ms=3,
              label=f"{noun} (every band)" if profile and measured
              else f"{noun} (band used: first ring to Nyquist)" if measured else f"{noun} (fitted band)")
    if not (profile and measured):
        ax.loglog(zeta, fit, "-", color="C3", lw=1.5,
                  label="--psd measured" if measured else "KC fit (its profile PSD)" if profile else "KC fit")
    ax.text(3.0 * ring_width, ax.get_ylim()[0], " periods > map / 3", fontsize=7, color="0.4", va="bottom")
    ax.set_ylabel(rf"$P(\zeta)$ [$\mu$m$^{unit}$]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="upper right")  # the PSD falls to the right: its upper right is empty
    if title:
        ax.set_title(wrap(title, 0.9 * fig.get_figwidth() / spec.get_geometry()[1], 9), fontsize=9)
    ratio = psd / fit
    ax_res.semilogx(zeta[~band], ratio[~band], ".", color="0.6", ms=3)
    ax_res.semilogx(zeta[band], ratio[band], ".", color="C0", ms=3)
    ax_res.axhline(1.0, color="C3", lw=1)
    ax_res.set_ylim(0, 2.5)
    ax_res.set_xlabel(r"$\zeta$ [rad/$\mu$m]")
    ax_res.set_ylabel("data / model" if measured else "data / fit")
    ax_res.grid(True, which="both", alpha=0.3)


def image_panel(fig, spec, image, extent):
    ax = fig.add_subplot(spec[:, 1])
    positive = image[image > 0]
    # Masked estimates can dip below zero where the PSD is far below their scatter: shown at the floor.
    floor = positive.min() if positive.size else 1.0
    shown = ax.imshow(np.log10(np.maximum(image, floor)), origin="lower", extent=extent, cmap="magma",
                      interpolation="nearest", aspect="equal")
    ax.set_xlabel(r"$\zeta_x$ [rad/$\mu$m]")
    ax.set_ylabel(r"$\zeta_y$ [rad/$\mu$m]")
    ax.set_title("2-D PSD (log scale)", fontsize=9)
    fig.colorbar(shown, ax=ax, label=r"$\log_{10} P$ [$\mu$m$^4$]", shrink=0.8)


def main():
    if len(sys.argv) not in (3, 4, 9):
        sys.exit(__doc__)
    data = np.genfromtxt(sys.argv[1], delimiter=",", names=True)
    title = sys.argv[3] if len(sys.argv) > 3 else ""
    with_image = len(sys.argv) == 9
    fig = plt.figure(figsize=(13 if with_image else 7, 6.5))
    spec = fig.add_gridspec(2, 2 if with_image else 1, height_ratios=[3, 1],
                            width_ratios=[1, 1] if with_image else None)
    radial_panels(fig, spec, data, title)
    if with_image:
        image_panel(fig, spec, np.load(sys.argv[4]), [float(v) for v in sys.argv[5:9]])
    fig.tight_layout()
    save(fig, sys.argv[2], dpi=120)


if __name__ == "__main__":
    run(main)
