"""The 2-D PSD of a height map beside its elliptical KC fit and their ratio (`surfscatter surface fit --plot`).

usage: psd2d_fit.py <data.npy> <fit.npy> <out.png> <title> <zeta_x_left> <zeta_x_right> <zeta_y_bottom> <zeta_y_top>
                    <zeta_min> <zeta_max> <lay_angle_deg>
The .npy files hold the periodogram the fit used and the fitted PSD (um^4) over the zeta-plane, centred, rows = zeta_y;
the four numbers are their outer edges (rad/um). The circles mark the fitted band, the line the lay direction u (the
PSD is elongated across it). The ratio is shown after 4 x 4 block means (a single bin scatters by ~100 %).
"""
import sys

from plotting import run, save, wrap  # this folder: atomic writes, one-line failures
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def block_mean(image, n):
    h, w = (image.shape[0] // n) * n, (image.shape[1] // n) * n
    return image[:h, :w].reshape(h // n, n, w // n, n).mean(axis=(1, 3))


def decorate(ax, zeta_min, zeta_max, lay_deg, extent):
    for radius in (zeta_min, zeta_max):
        ax.add_patch(plt.Circle((0, 0), radius, fill=False, color="w", lw=0.8, ls="--"))
    reach = max(abs(v) for v in extent)
    c, s = np.cos(np.radians(lay_deg)), np.sin(np.radians(lay_deg))
    ax.plot([-reach * c, reach * c], [-reach * s, reach * s], color="c", lw=0.8, label="lay u")
    ax.set_xlim(extent[0], extent[1])
    ax.set_ylim(extent[2], extent[3])
    ax.set_xlabel(r"$\zeta_x$ [rad/$\mu$m]")
    ax.set_ylabel(r"$\zeta_y$ [rad/$\mu$m]")


def main():
    if len(sys.argv) != 12:
        sys.exit(__doc__)
    data, fit = np.load(sys.argv[1]), np.load(sys.argv[2])
    extent = [float(v) for v in sys.argv[5:9]]
    zeta_min, zeta_max, lay = (float(v) for v in sys.argv[9:12])
    positive = data[data > 0]
    # The colour scale starts at the 1st percentile of the positive bins: the DC bin (the mean, removed) and masked
    # estimates that dip below zero where the PSD is far below their scatter are shown at that floor.
    low = np.percentile(np.log10(positive), 1) if positive.size else 0.0
    log_data = np.log10(np.maximum(data, 10.0**low))
    log_fit = np.log10(np.maximum(fit, 10.0**low))
    high = log_data.max()
    fig, axes = plt.subplots(1, 3, figsize=(16, 5.6))
    for ax, image, name in ((axes[0], log_data, "2-D periodogram (log scale)"),
                            (axes[1], log_fit, "elliptical KC fit (log scale)")):
        shown = ax.imshow(image, origin="lower", extent=extent, cmap="magma", vmin=low, vmax=high,
                          interpolation="nearest", aspect="equal")
        decorate(ax, zeta_min, zeta_max, lay, extent)
        ax.set_title(name, fontsize=9)
        fig.colorbar(shown, ax=ax, label=r"$\log_{10} P$ [$\mu$m$^4$]", shrink=0.8)
    ratio = block_mean(np.maximum(data, 0.0), 4) / np.maximum(block_mean(fit, 4), 1e-300)
    shown = axes[2].imshow(np.log2(np.maximum(ratio, 1e-3)), origin="lower", extent=extent, cmap="RdBu_r", vmin=-1.5,
                           vmax=1.5, interpolation="nearest", aspect="equal")
    decorate(axes[2], zeta_min, zeta_max, lay, extent)
    axes[2].set_title("data / fit (4 x 4 bin means)", fontsize=9)
    fig.colorbar(shown, ax=axes[2], label=r"$\log_2$(data / fit)", shrink=0.8)
    axes[0].legend(loc="upper right")
    fig.suptitle(wrap(sys.argv[4], 0.95 * fig.get_figwidth(), 10), fontsize=10)
    fig.tight_layout()
    save(fig, sys.argv[3], dpi=110)


if __name__ == "__main__":
    run(main)
