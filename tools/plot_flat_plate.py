#!/usr/bin/python3
"""Flat-plate report: local skin friction c_f(Re_x) against the
Prandtl-Schlichting formula and the velocity profile u+(y+) against the log
law, from the flat_plate.h5 that tests/cfd/turbulence/flat_plate_test.cc
writes (KELVIN_REPORT_DIR).

Usage: tools/plot_flat_plate.py REPORT_DIR   (writes flat_plate_cf.png and flat_plate_uplus.png there)
"""
import math
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    directory = sys.argv[1]
    path = os.path.join(directory, "flat_plate.h5")
    if not os.path.exists(path):
        sys.exit(f"plot_flat_plate: {path} not found (run flat_plate_test with KELVIN_REPORT_DIR set)")
    with h5py.File(path, "r") as f:
        runs = {name: (g["x"][()], g["cf"][()], g["y_plus"][()], g["u_plus"][()], dict(g.attrs))
                for name, g in f["runs"].items()}
    fig, ax = plt.subplots(figsize=(7, 4.5))
    re_min, re_max = math.inf, 0.0
    for name, (x, cf, _, _, attrs) in sorted(runs.items()):
        re_x = attrs["reynolds"] * x
        keep = re_x > 0
        ax.semilogx(re_x[keep], cf[keep], label=f"kelvin SST {name} (C_F {attrs['C_F']:.4e})")
        re_min, re_max = min(re_min, re_x[keep].min()), max(re_max, re_x[keep].max())
    grid = [10 ** (math.log10(re_min) + i * (math.log10(re_max) - math.log10(re_min)) / 200) for i in range(201)]
    ax.semilogx(grid, [(2 * math.log10(r) - 0.65) ** -2.3 for r in grid], "k--",
                label="Prandtl-Schlichting (2 log Re_x - 0.65)^-2.3")
    ax.set_xlabel("Re_x")
    ax.set_ylabel("c_f")
    ax.set_ylim(0, 0.008)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    ax.set_title("Zero-pressure-gradient flat plate: local skin friction")
    fig.tight_layout()
    fig.savefig(os.path.join(directory, "flat_plate_cf.png"), dpi=120)

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for name, (_, _, yp, up, attrs) in sorted(runs.items()):
        keep = yp < 5000
        ax.semilogx(yp[keep], up[keep], "o-", ms=3, label=f"{name}, x = {attrs['x_profile']:.2f} L")
    yl = [10 ** (1 + 3 * i / 100) for i in range(101)]
    ax.semilogx(yl, [math.log(y) / 0.41 + 5.0 for y in yl], "k--", lw=0.8, label="log law, kappa 0.41, B 5.0")
    ax.semilogx(yl, [math.log(y) / 0.41 + 5.2 for y in yl], "k:", lw=0.8, label="log law, kappa 0.41, B 5.2")
    ax.axvspan(50, 300, color="0.9", label="checked range 50 < y+ < 300")
    ax.set_xlabel("y+")
    ax.set_ylabel("u+")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    ax.set_title("Velocity profile in wall units")
    fig.tight_layout()
    fig.savefig(os.path.join(directory, "flat_plate_uplus.png"), dpi=120)
    print(f"wrote {directory}/flat_plate_cf.png and flat_plate_uplus.png ({len(runs)} runs)")


if __name__ == "__main__":
    main()
