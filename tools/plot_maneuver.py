#!/usr/bin/python3
"""Plots kelvin maneuver results (HDF5 from `kelvin simulate`) to PNG.

For each file: the track of midship seen from above (y to starboard on the
horizontal axis, the initial heading up), heading and rudder angle against
time, and yaw rate against time, with the key metrics in the title.

Usage: tools/plot_maneuver.py results/simulate/*.h5 [-o out_dir]
"""
import argparse
import math
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def text(value):
    """HDF5 string attributes arrive as bytes or str depending on their type."""
    return value.decode() if isinstance(value, bytes) else str(value)


def read(path):
    with h5py.File(path, "r") as f:
        if text(f.attrs.get("kelvin_schema", b"")) != "maneuver/1":
            raise ValueError(f"{path}: not a kelvin maneuver file (attribute kelvin_schema != 'maneuver/1')")
        tr = {k: f["trajectory"][k][()] for k in f["trajectory"]}
        metrics = {k: (float(f["metrics"][k][0]), text(f["metrics"][k].attrs["units"])) for k in f["metrics"]}
        attrs = {k: f.attrs[k] if not isinstance(f.attrs[k], bytes) else text(f.attrs[k]) for k in f.attrs}
    return tr, metrics, attrs


def plot(path, out_dir):
    tr, metrics, attrs = read(path)
    L = float(attrs["Lpp"])
    name = f"{attrs['ship']} {attrs['maneuver']}"
    fig, axes = plt.subplots(1, 3, figsize=(15, 5))
    ax = axes[0]
    ax.plot(tr["y"] / L, tr["x"] / L, lw=1.5)
    ax.set_xlabel("y / L (starboard)")
    ax.set_ylabel("x / L (initial heading)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.3)
    ax.set_title("track of midship")
    ax = axes[1]
    ax.plot(tr["time"], [math.degrees(p) for p in tr["psi"]], label="heading ψ")
    ax.plot(tr["time"], [math.degrees(d) for d in tr["rudder"]], label="rudder δ")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("deg")
    ax.grid(True, alpha=0.3)
    ax.legend()
    ax.set_title("heading and rudder")
    ax = axes[2]
    ax.plot(tr["time"], [math.degrees(r) for r in tr["r"]])
    ax.set_xlabel("t (s)")
    ax.set_ylabel("yaw rate r (deg/s)")
    ax.grid(True, alpha=0.3)
    ax.set_title("yaw rate")
    keys = [k for k in ("advance_over_L", "tactical_diameter_over_L", "first_overshoot", "second_overshoot")
            if k in metrics]
    summary = ", ".join(f"{k} = {metrics[k][0]:.3g} {metrics[k][1] if metrics[k][1] != '1' else ''}".strip()
                        for k in keys)
    fig.suptitle(f"{name}   {summary}")
    fig.tight_layout()
    os.makedirs(out_dir, exist_ok=True)
    out = os.path.join(out_dir, os.path.splitext(os.path.basename(path))[0] + ".png")
    tmp = out + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    plt.close(fig)
    os.replace(tmp, out)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="+", help="maneuver HDF5 files from kelvin simulate")
    ap.add_argument("-o", "--output", help="output directory (default: beside each file)")
    a = ap.parse_args()
    status = 0
    for path in a.files:
        try:
            print(plot(path, a.output or os.path.dirname(path) or "."))
        except (OSError, KeyError, ValueError) as e:
            print(f"plot_maneuver: error: {path}: {e}", file=sys.stderr)
            status = 1
    return status


if __name__ == "__main__":
    sys.exit(main())
