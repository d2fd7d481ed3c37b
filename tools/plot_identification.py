#!/usr/bin/python3
"""Plots measured against fitted forces of a kelvin identification, per run.

Reads the HDF5 file `kelvin identify` writes beside its YAML output (schema
kelvin.derivatives/1) and writes one PNG per run: X', Y' and N' (prime
system) against time, the measured hydrodynamic force (rigid-body inertia
removed) as dots and the joint fit as a line, with the analysis window
(whole periods after the ramp-up) shaded and the RMS residual in each panel.

Usage: tools/plot_identification.py derivatives.h5 [-o out_dir]
"""
import argparse
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def text(value):
    """HDF5 string attributes arrive as bytes or str depending on their type."""
    return value.decode() if isinstance(value, bytes) else str(value)


def read_runs(path):
    with h5py.File(path, "r") as f:
        if text(f.attrs.get("schema", b"")) != "kelvin.derivatives/1":
            raise ValueError(f"{path}: not a kelvin derivative file (attribute schema != 'kelvin.derivatives/1')")
        ship = text(f.attrs.get("ship", b""))
        runs = []
        for name, g in f["runs"].items():
            run = {
                "name": name,
                "kind": text(g.attrs["kind"]),
                "begin": int(g.attrs["window_begin"]),
                "end": int(g.attrs["window_end"]),
                "time": np.asarray(g["time"]),
            }
            for ch in ("X", "Y", "N"):
                for what in ("measured", "fitted"):
                    key = f"{what}_{ch}"
                    if key not in g:
                        raise ValueError(f"{path}: run '{name}': dataset '{key}' is missing")
                    run[key] = np.asarray(g[key])
            runs.append(run)
    return ship, runs


def plot_run(ship, run, out_dir):
    t = run["time"]
    b, e = run["begin"], run["end"]
    fig, axes = plt.subplots(3, 1, figsize=(9, 7.5), sharex=True)
    for ax, ch in zip(axes, ("X", "Y", "N")):
        meas, fit = run[f"measured_{ch}"], run[f"fitted_{ch}"]
        ax.axvspan(t[b], t[e - 1], color="0.93", label="analysis window")
        ax.plot(t, meas, ".", ms=2, color="tab:blue", label="measured")
        ax.plot(t, fit, "-", lw=1.2, color="tab:red", label="joint fit")
        rms = float(np.sqrt(np.mean((meas[b:e] - fit[b:e]) ** 2)))
        ax.set_ylabel(f"{ch}'")
        ax.set_title(f"{ch}': RMS residual {rms:.3g} over the window", fontsize=9, loc="right")
        ax.grid(True, lw=0.3)
    axes[0].legend(loc="upper left", fontsize=8, ncol=3)
    axes[-1].set_xlabel("time [s]")
    fig.suptitle(f"{ship} {run['name']} ({run['kind']}): measured vs fitted, prime system")
    fig.tight_layout()
    out = os.path.join(out_dir, f"{run['name']}.png")
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("derivatives", help="HDF5 output of kelvin identify")
    parser.add_argument("-o", "--out-dir", default=None, help="output directory (default: beside the input)")
    args = parser.parse_args(argv)
    try:
        ship, runs = read_runs(args.derivatives)
    except (OSError, KeyError, ValueError) as err:
        print(f"plot_identification: error: {err}", file=sys.stderr)
        return 1
    out_dir = args.out_dir or os.path.splitext(args.derivatives)[0] + "_plots"
    os.makedirs(out_dir, exist_ok=True)
    for run in runs:
        print(f"  written: {plot_run(ship, run, out_dir)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
