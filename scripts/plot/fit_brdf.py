#!/usr/bin/python3
"""The measured BRDF against each model's fit from `surfscatter fit-brdf`: per model, the slice in the plane of
incidence (measured points, fitted curves, one colour per wavelength) and the map of the residuals over the outgoing
direction cosines.
Usage: fit_brdf.py OUT.csv OUT.json OUT_residuals.png"""
import csv
import json
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    csv_path, json_path, out = sys.argv[1], sys.argv[2], sys.argv[3]
    with open(csv_path) as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    meta = json.load(open(json_path))
    models = [m["model"] for m in meta["models"]]
    errors = meta["data"]["with_errors"]
    profile = meta.get("profile")  # 1-D data: intensity per radian, all in the plane of incidence
    wavelengths = sorted({r["wavelength_nm"] for r in rows})
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    fig, axes = plt.subplots(len(models), 2, figsize=(11, 3.6 * len(models)), squeeze=False)
    for i, (name, fit) in enumerate(zip(models, meta["models"])):
        ax, am = axes[i]
        # In-plane: outgoing azimuth within 3 degrees of the incidence plane; signed theta_o (negative: the side of
        # the light).
        for w, c in zip(wavelengths, colours):
            pts = []
            for r in rows:
                if r["wavelength_nm"] != w:
                    continue
                d = (r["phi_o_deg"] - r["phi_i_deg"]) % 360
                if min(d, 360 - d) < 3 or r["theta_o_deg"] == 0:
                    pts.append((-r["theta_o_deg"], r["brdf"], r[f"{name}_fit"]))
                elif abs(d - 180) < 3:
                    pts.append((r["theta_o_deg"], r["brdf"], r[f"{name}_fit"]))
            pts.sort()
            if pts:
                ax.semilogy([p[0] for p in pts], [p[1] for p in pts], "o", ms=3, color=c, label=f"measured {w:g} nm")
                ax.semilogy([p[0] for p in pts], [p[2] for p in pts], "-", color=c, lw=1.2, label=f"fit {w:g} nm")
        ax.set_xlabel("theta_o in the plane of incidence (deg; > 0: specular side)")
        ax.set_ylabel(f"{profile}-polarised intensity (1/rad)" if profile else "BRDF (1/sr)")
        ax.set_title(fit["summary"], fontsize=7, wrap=True)
        ax.legend(fontsize=6, ncol=2)
        ax.grid(alpha=0.3)
        res = [r[f"{name}_residual"] for r in rows]
        lim = max(1e-12, sorted(abs(v) for v in res)[int(0.95 * (len(res) - 1))])
        label = "(fit - data) / stderr" if errors else "(fit - data) / data"
        if profile:
            # In-plane only: the residual against the signed theta_o, one colour per wavelength.
            for w, c in zip(wavelengths, colours):
                pts = [(r["theta_o_deg"] * (1 if math.cos(math.radians(r["phi_o_deg"])) < 0 else -1),
                        r[f"{name}_residual"]) for r in rows if r["wavelength_nm"] == w]
                am.plot([p[0] for p in pts], [p[1] for p in pts], "o", ms=3, color=c, label=f"{w:g} nm")
            am.axhline(0, color="k", lw=0.6)
            am.set_xlabel("theta_o in the plane of incidence (deg; > 0: specular side)")
            am.set_ylabel(label)
            am.set_title(f"{name}: residual", fontsize=8)
            am.legend(fontsize=6)
            am.grid(alpha=0.3)
            continue
        ox = [math.sin(math.radians(r["theta_o_deg"])) * math.cos(math.radians(r["phi_o_deg"])) for r in rows]
        oy = [math.sin(math.radians(r["theta_o_deg"])) * math.sin(math.radians(r["phi_o_deg"])) for r in rows]
        sc = am.scatter(ox, oy, c=res, s=6, cmap="RdBu_r", vmin=-lim, vmax=lim)
        am.set_aspect("equal")
        am.set_xlabel("o_x = sin theta_o cos phi_o")
        am.set_ylabel("o_y = sin theta_o sin phi_o")
        am.set_title(f"{name}: residual, all wavelengths", fontsize=8)
        fig.colorbar(sc, ax=am, label=label)
    fig.suptitle(meta["verdict"], fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
