"""Radial PSD of a height map with its KC fit (written by `surfscatter surface fit --plot`).

usage: psd_fit.py <psd.csv> <out.png> [title]
The CSV has columns zeta (rad/um), psd (um^4), count, kc_fit (um^4), in_band (1 if the ring was fitted).
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: psd_fit.py <psd.csv> <out.png> [title]")
    data = np.genfromtxt(sys.argv[1], delimiter=",", names=True)
    zeta, psd, fit, band = data["zeta"], data["psd"], data["kc_fit"], data["in_band"] > 0.5
    fig, (ax, ax_res) = plt.subplots(2, 1, figsize=(7, 6.5), sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    ax.loglog(zeta[~band], psd[~band], ".", color="0.6", ms=3, label="radial PSD (not fitted)")
    ax.loglog(zeta[band], psd[band], ".", color="C0", ms=3, label="radial PSD (fitted band)")
    ax.loglog(zeta, fit, "-", color="C3", lw=1.5, label="KC fit")
    ax.set_ylabel(r"$P(\zeta)$ [$\mu$m$^4$]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="lower left")
    if len(sys.argv) > 3:
        ax.set_title(sys.argv[3], fontsize=9)
    ratio = psd / fit
    ax_res.semilogx(zeta[~band], ratio[~band], ".", color="0.6", ms=3)
    ax_res.semilogx(zeta[band], ratio[band], ".", color="C0", ms=3)
    ax_res.axhline(1.0, color="C3", lw=1)
    ax_res.set_ylim(0, 2.5)
    ax_res.set_xlabel(r"$\zeta$ [rad/$\mu$m]")
    ax_res.set_ylabel("data / fit")
    ax_res.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=120)


if __name__ == "__main__":
    main()
