#!/usr/bin/python3
"""Plots kelvin maneuver results (HDF5 from `kelvin simulate`) to PNG.

For each file: the track of midship seen from above (y to starboard on the
horizontal axis, the initial heading up), heading and rudder angle against
time, and yaw rate against time, with the key metrics in the title.

With --overlay, each file is drawn together with another maneuver file of
the same maneuver (kelvin check writes the surrogate runs of the references
it checked, surrogate_<i>_<reference>.h5 in its report directory): both
tracks in axes of their own position and heading at the rudder execute, and
both time histories against the time since the execute, so that a reference
(free-running CFD, or the simulator) and its surrogate can be compared. The
PNG is then <file>_vs_<overlay>.png.

Usage: tools/plot_maneuver.py results/simulate/*.h5 [-o out_dir]
       tools/plot_maneuver.py REF.h5 [REF2.h5 ...] --overlay SURROGATE.h5 [SURROGATE2.h5 ...] [-o out_dir]
"""
import argparse
import math
import os
import sys

import h5py
import matplotlib
import numpy

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
        tr["execute_times"] = f["execute_times"][()] if "execute_times" in f else []
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


def execute_frame(tr):
    """Time since the first rudder execute and midship position in axes of
    the position and heading at that instant (x along, y to starboard)."""
    t = tr["time"]
    t0 = float(tr["execute_times"][0]) if len(tr["execute_times"]) else float(t[0])
    x0, y0, psi0 = (float(numpy.interp(t0, t, tr[k])) for k in ("x", "y", "psi"))
    dx, dy = tr["x"] - x0, tr["y"] - y0
    c, s = math.cos(psi0), math.sin(psi0)
    return t - t0, dx * c + dy * s, -dx * s + dy * c, tr["psi"] - psi0


def label(path, attrs):
    return f"{attrs.get('source', 'simulator')}: {os.path.basename(path)}"


def plot_overlay(path, overlay, out_dir):
    """`path` and `overlay` on the same axes, against the time since execute."""
    runs = [(path, *read(path)), (overlay, *read(overlay))]
    L = float(runs[0][3]["Lpp"])
    name = f"{runs[0][3]['ship']} {runs[0][3]['maneuver']}"
    if runs[1][3]["maneuver"] != runs[0][3]["maneuver"]:
        raise ValueError(f"--overlay {overlay}: maneuver {runs[1][3]['maneuver']}, expected {runs[0][3]['maneuver']}")
    fig, axes = plt.subplots(1, 3, figsize=(15, 5))
    for (p, tr, metrics, attrs), style, color in zip(runs, ("-", "--"), ("C0", "C1")):
        t, along, across, dpsi = execute_frame(tr)
        lab = label(p, attrs)
        axes[0].plot(across / L, along / L, style, color=color, lw=1.5, label=lab)
        axes[1].plot(t, [math.degrees(v) for v in dpsi], style, color=color, label=f"ψ - ψ0, {lab}")
        axes[1].plot(t, [math.degrees(d) for d in tr["rudder"]], style, color=color, lw=0.8, alpha=0.6,
                     label=f"δ, {lab}")
        axes[2].plot(t, [math.degrees(r) for r in tr["r"]], style, color=color, label=lab)
    axes[0].set_xlabel("across / L (starboard, from execute)")
    axes[0].set_ylabel("along / L (heading at execute)")
    axes[0].set_aspect("equal", adjustable="datalim")
    axes[0].set_title("track of midship")
    axes[1].set_xlabel("t - t_execute (s)")
    axes[1].set_ylabel("deg")
    axes[1].set_title("heading change and rudder")
    axes[2].set_xlabel("t - t_execute (s)")
    axes[2].set_ylabel("yaw rate r (deg/s)")
    axes[2].set_title("yaw rate")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    keys = [k for k in ("advance_over_L", "tactical_diameter_over_L", "first_overshoot", "second_overshoot")
            if k in runs[0][2] and k in runs[1][2]]
    summary = ", ".join(f"{k} {runs[0][2][k][0]:.3g} / {runs[1][2][k][0]:.3g}" for k in keys)
    fig.suptitle(f"{name}   {summary}")
    fig.tight_layout()
    os.makedirs(out_dir, exist_ok=True)
    stem = os.path.splitext(os.path.basename(path))[0]
    out = os.path.join(out_dir, f"{stem}_vs_{os.path.splitext(os.path.basename(overlay))[0]}.png")
    tmp = out + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    plt.close(fig)
    os.replace(tmp, out)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="+", help="maneuver HDF5 files from kelvin simulate")
    ap.add_argument("-o", "--output", help="output directory (default: beside each file)")
    ap.add_argument("--overlay", nargs="+", metavar="FILE",
                    help="one maneuver file per file to draw with it (e.g. kelvin check's surrogate runs)")
    a = ap.parse_args()
    if a.overlay and len(a.overlay) != len(a.files):
        ap.error(f"--overlay: {len(a.overlay)} files for {len(a.files)} files to plot; expected one per file")
    status = 0
    for i, path in enumerate(a.files):
        try:
            out_dir = a.output or os.path.dirname(path) or "."
            print(plot_overlay(path, a.overlay[i], out_dir) if a.overlay else plot(path, out_dir))
        except (OSError, KeyError, ValueError) as e:
            print(f"plot_maneuver: error: {path}: {e}", file=sys.stderr)
            status = 1
    return status


if __name__ == "__main__":
    sys.exit(main())
