#!/usr/bin/python3
"""The worked example of docs/PYTHON.md: from a measured height map to a rendering, in Python.

1. load a height map (any format surfscatter reads) and fit a K-correlation PSD to it;
2. plot its radial PSD with the fit and the map's own tabulated PSD;
3. compare GHS, its smooth-surface approximation, GGX and the two-scale model on in-plane slices;
4. render the reference photo setup with the fitted surface and show it.

Run from the repository with the package of the build tree:
    PYTHONPATH=build/python /usr/bin/python3 examples/python_walkthrough.py --out out/walkthrough
(--show opens the figures in windows; `make test` runs it headless, with matplotlib's Agg backend.)
"""

import argparse
from pathlib import Path

import matplotlib
import matplotlib.pyplot as plt
import numpy as np

import surfscatter as ss

REPOSITORY = Path(__file__).resolve().parents[1]


def arguments():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("height_map", nargs="?", type=Path,
                        default=REPOSITORY / "examples" / "data" / "kc_surface.gsf",
                        help="height map file (default: the synthetic KC surface of examples/data, "
                             "sigma 0.05 um, L 2 um, gamma 3)")
    parser.add_argument("--material", default="Al", help="metal of the sample (default Al)")
    parser.add_argument("--wavelength", type=float, default=550.0, help="wavelength of the slices in nm")
    parser.add_argument("--spp", type=int, default=16, help="samples per pixel of the rendering")
    parser.add_argument("--width", type=int, default=256, help="width of the rendering in pixels")
    parser.add_argument("--out", type=Path, default=Path("out/walkthrough"), help="output directory")
    parser.add_argument("--show", action="store_true", help="open the figures in windows")
    return parser.parse_args()


def main():
    args = arguments()
    args.out.mkdir(parents=True, exist_ok=True)

    # 1. The height map and its K-correlation fit (as `surfscatter surface fit`).
    height_map = ss.read_height_map(args.height_map)
    print(height_map.describe())
    fit = ss.fit_surface(height_map, form="plane")
    print(f"KC fit: sigma_h = {fit.sigma_h:.4g} um, L = {fit.corr_length:.4g} um, gamma = {fit.gamma:.4g}, "
          f"rms slope {fit.rms_slope:.4g}")
    surface = fit.statistics  # a KCorrelation

    # 2. The radial PSD: the rings that were fitted, the fit, and the map's own PSD as statistics.
    rings = fit.radial
    measured = ss.measured_statistics(height_map)
    zeta = np.geomspace(rings["zeta"][0], rings["zeta"][-1], 200)
    in_band = (rings["zeta"] >= fit.zeta_min) & (rings["zeta"] <= fit.zeta_max)
    fig, ax = plt.subplots(figsize=(6, 4.2))
    ax.loglog(rings["zeta"][~in_band], rings["psd"][~in_band], ".", color="0.7", label="rings outside the band")
    ax.loglog(rings["zeta"][in_band], rings["psd"][in_band], ".", color="C0", label="rings fitted")
    ax.loglog(zeta, surface.psd(zeta), color="C3", label=f"KC fit, gamma = {fit.gamma:.3g}")
    ax.loglog(zeta, measured.psd(zeta), "--", color="C2", label="measured_statistics")
    ax.set_xlabel("zeta (rad/um)")
    ax.set_ylabel("P(zeta) (um^4)")
    ax.set_title(args.height_map.name)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out / "psd.png", dpi=120)

    # 3. In-plane slices at 30 degrees incidence: positive angles on the specular side.
    theta_i = 30.0
    theta_o = np.linspace(-89.5, 89.5, 717)
    wi = ss.direction(theta_i, 0.0)
    wo = ss.direction(np.abs(theta_o), np.where(theta_o >= 0, 180.0, 0.0))
    models = {
        "GHS": ss.bsdf("ghs", surface=surface, material=args.material),
        "GHS-SSA": ss.bsdf("ghs_ssa", surface=surface, material=args.material),
        "GGX (rms slope of the map)": ss.bsdf("ggx_stats", surface=height_map, alpha_from="measured",
                                              material=args.material),
        "two-scale": ss.bsdf("two_scale", surface=surface, material=args.material),
    }
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    slices = {}
    for (label, model), style in zip(models.items(), ["-", "--", "-", ":"]):
        total, specular = model.albedo(theta_i, args.wavelength)
        slices[label] = model.eval(wi, wo, args.wavelength)
        print(f"{label}: albedo {total:.4f}, of which the specular delta {specular:.4f}")
        ax.semilogy(theta_o, slices[label], style, lw=2 if style == "-" else 1.5,
                    label=f"{label}: albedo {total:.3f} (specular {specular:.3f})")
    # How the models differ on the slice, against GHS: near the mirror direction and away from it.
    away = np.abs(theta_o - theta_i)
    for label, values in slices.items():
        if label == "GHS":
            continue
        ratio = values / slices["GHS"]
        print(f"  {label} / GHS: up to {ratio[away <= 1].max():.4g} within 1 deg of the mirror direction, "
              f"{ratio[away > 10].min():.4g} to {ratio[away > 10].max():.4g} beyond 10 deg")
    ax.axvline(theta_i, color="0.8", lw=0.8)
    ax.set_xlabel("theta_o (deg), in the plane of incidence")
    ax.set_ylabel("f_r (1/sr)")
    ax.set_title(f"{args.material}, {args.wavelength:g} nm, theta_i = {theta_i:g} deg")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out / "slices.png", dpi=120)

    # 4. The reference photo setup with the fitted surface (scenes/photo-setup), linear sRGB.
    scene = REPOSITORY / "scenes" / "photo-setup" / "scene.xml"
    params = {"view": 1, "model": "ghs", "material": args.material, "sigma": fit.sigma_h,
              "corr_length": fit.corr_length, "gamma": fit.gamma,
              "width": args.width, "height": args.width * 3 // 4}
    result = ss.render(scene, spp=args.spp, params=params, seed=1)
    print(f"rendered {result['rgb'].shape[1]}x{result['rgb'].shape[0]} at {result['spp']} spp in "
          f"{result['seconds']:.1f} s")
    ss.write_photo(args.out / "render.exr", result["rgb"])
    ss.write_photo(args.out / "render.png", result["rgb"])
    rgb = np.clip(result["rgb"], 0.0, 1.0)
    srgb = np.where(rgb <= 0.0031308, 12.92 * rgb, 1.055 * rgb ** (1 / 2.4) - 0.055)
    fig, ax = plt.subplots(figsize=(6, 4.8))
    ax.imshow(srgb)
    ax.set_axis_off()
    ax.set_title("photo-setup view 1, GHS with the fitted surface")
    fig.tight_layout()
    fig.savefig(args.out / "render_view.png", dpi=120)

    print(f"wrote {args.out}/psd.png, slices.png, render.exr, render.png, render_view.png")
    if args.show and matplotlib.get_backend().lower() != "agg":
        plt.show()


if __name__ == "__main__":
    main()
