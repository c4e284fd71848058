"""What a height map's preparation did (`surfscatter surface info MAP --plot out.png` writes out_prepared.png).

usage: prepared_map.py <rings.csv> <heights.npy> <psd2d_read.npy> <psd2d_prepared.npy> <out.png> <title>
       <width_um> <height_um> <zeta_x_left> <zeta_x_right> <zeta_y_bottom> <zeta_y_top> <lambda_s_um> <lambda_c_um>
       <nyquist>
Panels: the prepared map (um); the 2-D PSD as read (mean removed only) and prepared, on one log colour scale; the ring
means of both and of the waviness (what the L-filter removed), with the band the map resolves (first ring to
Nyquist) and the nesting indices as zeta = 2 pi / lambda. lambda 0: that filter was not applied.
"""
import sys

import numpy as np

from plotting import PlotError, run, save, wrap
import matplotlib.pyplot as plt
from matplotlib.colors import LogNorm


def main(csv, heights, before, after, out, title, width, height, left, right, bottom, top, lambda_s, lambda_c,
         nyquist):
    try:
        rings = np.genfromtxt(csv, delimiter=",", names=True)
        h = np.load(heights)
        p_read, p_prepared = np.load(before), np.load(after)
    except OSError as error:
        raise PlotError(f"cannot read the plot's data: {error}") from None
    width, height, left, right, bottom, top = map(float, (width, height, left, right, bottom, top))
    lambda_s, lambda_c, nyquist = float(lambda_s), float(lambda_c), float(nyquist)

    fig = plt.figure(figsize=(14, 9.5))
    spec = fig.add_gridspec(2, 3, height_ratios=[1, 1.05], hspace=0.35, wspace=0.6)
    fig.suptitle(wrap(title, 13.5, 10), fontsize=10)

    ax = fig.add_subplot(spec[0, 0])
    image = ax.imshow(h, origin="lower", extent=(0, width, 0, height), cmap="viridis", aspect="equal")
    ax.set_title("prepared map", fontsize=10)
    ax.set_xlabel(r"x [$\mu$m]")
    ax.set_ylabel(r"y [$\mu$m]")
    fig.colorbar(image, ax=ax, shrink=0.8, label=r"height [$\mu$m]")

    positive = np.concatenate([p_read[p_read > 0].ravel(), p_prepared[p_prepared > 0].ravel()])
    norm = LogNorm(vmin=np.percentile(positive, 1), vmax=positive.max()) if positive.size else None
    for column, (data, name) in enumerate(((p_read, "2-D PSD as read"), (p_prepared, "2-D PSD prepared")), start=1):
        ax = fig.add_subplot(spec[0, column])
        image = ax.imshow(np.where(data > 0, data, np.nan), origin="lower", extent=(left, right, bottom, top),
                          cmap="magma", norm=norm, aspect="equal")
        ax.set_title(name, fontsize=10)
        ax.set_xlabel(r"$\zeta_x$ [rad/$\mu$m]")
        ax.set_ylabel(r"$\zeta_y$ [rad/$\mu$m]")
        fig.colorbar(image, ax=ax, shrink=0.8, label=r"$P$ [$\mu$m$^4$]")

    ax = fig.add_subplot(spec[1, :])
    zeta = rings["zeta"]
    for name, label, style in (("read", "as read (mean removed)", "C0"), ("prepared", "prepared", "C3"),
                               ("waviness", "waviness (removed by the L-filter)", "C2")):
        values = rings[name]
        keep = values > 0
        if keep.any():
            ax.loglog(zeta[keep], values[keep], ".-", color=style, ms=3, lw=0.8, label=label)
    ax.axvspan(zeta[0], nyquist, color="0.93", zorder=0, label="band the map resolves (first ring to Nyquist)")
    for value, name, color in ((lambda_c, r"$\lambda_c$", "C2"), (lambda_s, r"$\lambda_s$", "C4")):
        if value > 0:
            z = 2 * np.pi / value
            ax.axvline(z, color=color, ls="--", lw=1.2, label=f"{name} = {value:g} $\\mu$m ($\\zeta$ = {z:.3g} rad/$\\mu$m)")
    ax.set_xlabel(r"$\zeta$ [rad/$\mu$m]")
    ax.set_ylabel(r"ring mean $P(\zeta)$ [$\mu$m$^4$]")
    ax.set_title("ring means of the 2-D PSDs (Hann window)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="lower left")
    save(fig, out, dpi=100)


if __name__ == "__main__":
    if len(sys.argv) != 16:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    run(main, *sys.argv[1:])
