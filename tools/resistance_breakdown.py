#!/usr/bin/python3
"""Where on the hull the resistance acts: friction and pressure resistance of
a steady resistance run (`kelvin run` with a `resistance:` section) by hull
region, from the per-face forces in resistance.h5 (group hull_faces).

Usage: tools/resistance_breakdown.py RESULT_DIR [--double-body DB_DIR]
           [--x-ap X --length L] [--stations 0,0.05,0.25,0.75,0.95,1]
           [--near-surface 0.02] [--profile profile.png]

Regions along the hull by x' = (x - x_ap) / L (default: the hull faces' own
extent, x_ap its aft end and L its length), between the given stations (the
first and last region are open-ended, so faces aft of the AP and forward of
the FP are counted); beside them the faces within --near-surface metres of
z = 0 and the faces whose unit normal is within 25 deg of vertical (flat
bottom and shallow overhangs). With --double-body each row also shows the
same region of the double-body run and the difference (the region's share
of R_P - R_P(double body), i.e. of the wave-making part C_W). --profile
plots dR_P/dx and dR_F/dx along the hull (one or both runs).
"""
import argparse
import math
import os
import sys

import h5py
import numpy as np


def load(directory):
    path = os.path.join(directory, "resistance.h5")
    with h5py.File(path, "r") as f:
        if "hull_faces" not in f:
            raise SystemExit(f"{path}: no hull_faces group (rerun with a kelvin that writes it)")
        d = {k: f["hull_faces/" + k][:] for k in ("centre", "area", "pressure_force", "viscous_force", "direction")}
        for k in ("R_T", "R_F", "R_P", "speed", "rho", "wetted_area"):
            d[k] = float(f[k][0])
    d["rp"] = d["pressure_force"] @ d["direction"]
    d["rf"] = d["viscous_force"] @ d["direction"]
    return d


def regions(d, x_ap, length, stations, near_surface):
    c = d["centre"]
    xs = (c[:, 0] - x_ap) / length
    n = d["area"] / np.linalg.norm(d["area"], axis=1)[:, None]
    out = []
    for k in range(len(stations) - 1):
        lo = -math.inf if k == 0 else stations[k]
        hi = math.inf if k == len(stations) - 2 else stations[k + 1]
        out.append((f"x/L {stations[k]:.2f} to {stations[k + 1]:.2f}", (xs >= lo) & (xs < hi)))
    out.append((f"z > -{near_surface:g} m (near the waterline)", c[:, 2] > -near_surface))
    out.append(("normal within 25 deg of vertical", np.abs(n[:, 2]) > math.cos(math.radians(25.0))))
    out.append(("whole hull", np.ones(len(xs), bool)))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("result")
    ap.add_argument("--double-body", help="result directory of the double-body run on the same grid")
    ap.add_argument("--x-ap", type=float, help="x of the aft perpendicular (m)")
    ap.add_argument("--length", type=float, help="Lpp (m)")
    ap.add_argument("--stations", default="0,0.05,0.25,0.75,0.95,1", help="region bounds in x/L")
    ap.add_argument("--near-surface", type=float, default=0.02, help="depth band below z = 0 (m)")
    ap.add_argument("--profile", help="PNG of dR/dx along the hull")
    a = ap.parse_args()
    runs = [("run", load(a.result))]
    if a.double_body:
        runs.append(("double body", load(a.double_body)))
    c = runs[0][1]["centre"]
    x_ap = a.x_ap if a.x_ap is not None else c[:, 0].min()
    length = a.length if a.length is not None else c[:, 0].max() - c[:, 0].min()
    stations = [float(s) for s in a.stations.split(",")]
    d0 = runs[0][1]
    q = 0.5 * d0["rho"] * d0["speed"] ** 2 * d0["wetted_area"]
    print(f"{a.result}: R_T {d0['R_T']:.4g} N, R_F {d0['R_F']:.4g} N, R_P {d0['R_P']:.4g} N "
          f"(x_ap {x_ap:.4g} m, L {length:.4g} m, q S = {q:.4g} N)")
    head = "| region | faces | area (m^2) | R_F (N) | R_P (N) |"
    if a.double_body:
        head += " R_F db (N) | R_P db (N) | R_P - R_P db (N) | C_P - C_P db |"
    print(head)
    print("|" + " --- |" * (head.count("|") - 1))
    regs = [regions(d, x_ap, length, stations, a.near_surface) for _, d in runs]
    for k, (name, m) in enumerate(regs[0]):
        area = np.linalg.norm(d0["area"][m], axis=1).sum()
        row = f"| {name} | {m.sum()} | {area:.4f} | {d0['rf'][m].sum():+.3f} | {d0['rp'][m].sum():+.3f} |"
        if a.double_body:
            db = runs[1][1]
            mdb = regs[1][k][1]
            dp = d0["rp"][m].sum() - db["rp"][mdb].sum()
            row += f" {db['rf'][mdb].sum():+.3f} | {db['rp'][mdb].sum():+.3f} | {dp:+.3f} | {dp / q:+.3e} |"
        print(row)
    if a.profile:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(9, 4))
        bins = np.linspace(c[:, 0].min(), c[:, 0].max(), 61)
        mid = 0.5 * (bins[1:] + bins[:-1])
        for label, d in runs:
            for key, style in (("rp", "-"), ("rf", "--")):
                h, _ = np.histogram(d["centre"][:, 0], bins, weights=d[key])
                ax.plot((mid - x_ap) / length, h / np.diff(bins), style,
                        label=f"{label}: dR_{'P' if key == 'rp' else 'F'}/dx")
        ax.axhline(0, color="k", lw=0.5)
        ax.set_xlabel("(x - x_AP) / L")
        ax.set_ylabel("N/m")
        ax.legend()
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(a.profile, dpi=120)
        print(f"wrote {a.profile}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
