"""Self-convolutions of the unit-mass KC PSD and their refit (the supplemental's Fig. 2), written by
`surfscatter selfconv --plot`.

usage: selfconv.py <curves.csv> <table.csv> <out.png> [title]
curves.csv: zeta (rad/um), then true_<m>, fit_<m> (um^2) for a few orders m; table.csv: m, L_m (um), misfit.
Main axes: P-hat^{*m} (solid) and the KC refit with L_m (dashed), log-log. Inset: L_m against m, log-log, with the
fitted power law L m^-x.
"""
import sys

from plotting import run, save  # this folder: atomic writes, one-line failures
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import matplotlib.ticker
import numpy as np


def main():
    if len(sys.argv) < 4:
        sys.exit("usage: selfconv.py <curves.csv> <table.csv> <out.png> [title]")
    curves = np.genfromtxt(sys.argv[1], delimiter=",", names=True)
    table = np.genfromtxt(sys.argv[2], delimiter=",", names=True)
    zeta = curves["zeta"]
    orders = [int(name.split("_")[1]) for name in curves.dtype.names if name.startswith("true_")]
    fig, ax = plt.subplots(figsize=(7.5, 5.5))
    colours = plt.cm.viridis(np.linspace(0.0, 0.9, len(orders)))
    for colour, m in zip(colours, orders):
        ax.loglog(zeta, curves[f"true_{m}"], "-", color=colour, lw=1.6, label=f"m = {m}")
        ax.loglog(zeta, curves[f"fit_{m}"], "--", color=colour, lw=1.0)
    ax.set_xlabel(r"$\zeta$ [rad/$\mu$m]")
    ax.set_ylabel(r"$\hat P^{*m}(\zeta)$ [$\mu$m$^2$]  (solid: exact, dashed: KC refit)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="lower left")
    positive = np.concatenate([curves[f"true_{m}"] for m in orders])
    positive = positive[positive > 0]
    ax.set_ylim(max(positive.min(), positive.max() * 1e-14), positive.max() * 3)
    if len(sys.argv) > 4:
        ax.set_title(sys.argv[4], fontsize=9)

    m = np.atleast_1d(table["m"])
    lm = np.atleast_1d(table["L_m"])
    inset = ax.inset_axes([0.62, 0.58, 0.35, 0.38])
    inset.loglog(m, lm, "o", ms=3, color="C3", label=r"refit $L_m$")
    if len(m) > 1:
        x = -np.sum(np.log(m) * np.log(lm / lm[0])) / np.sum(np.log(m) ** 2)
        inset.loglog(m, lm[0] * m ** (-x), "-", color="k", lw=1, label=rf"$L\,m^{{-{x:.3f}}}$")
    inset.set_xlabel("m", fontsize=8)
    inset.set_ylabel(r"$L_m$ [$\mu$m]", fontsize=8)
    inset.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    inset.tick_params(labelsize=7)
    inset.legend()
    fig.tight_layout()
    save(fig, sys.argv[3], dpi=150)


if __name__ == "__main__":
    run(main)
