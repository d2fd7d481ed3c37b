#!/usr/bin/python3
"""Plots of a steady resistance run (`kelvin run` with a `resistance:` section).

Usage: tools/plot_resistance.py RESULT_DIR [RESULT_DIR ...]

Reads RESULT_DIR/resistance.h5 and writes next to it
  wave_cuts.png     eta along the y = const cuts (x / L)
  wave_profile.png  eta along the hull waterline, port and starboard
  wave_pattern.png  eta over the free surface (plan view, x / L and y / L), with
                    the Kelvin wedge (19.47 deg) drawn from the bow
  convergence.png   R_T, R_F, R_P and the relative changes per window
"""
import math
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def scalar(f, name, default=math.nan):
    return float(f[name][0]) if name in f else default


def plot_pattern(f, length, title, out):
    """Plan view of eta on the free-surface faces (triangulated centres)."""
    x = f["surface/x"][:] / length
    y = f["surface/y"][:] / length
    eta = f["surface/eta"][:] / length * 1e3
    lim = float(np.percentile(np.abs(eta), 99.5)) or 1.0
    fig, ax = plt.subplots(figsize=(10, 4.5))
    cs = ax.tricontourf(x, y, eta, levels=np.linspace(-lim, lim, 25), cmap="RdBu_r", extend="both")
    fig.colorbar(cs, ax=ax, label="eta / L x 1000")
    # Kelvin wedge from the bow (the largest x of the hull waterline if
    # known, else the patch's x at the hole), trailing toward smaller x.
    if "wave_profile/x" in f and len(f["wave_profile/x"]):
        bow = float(np.max(f["wave_profile/x"][:])) / length
        span = bow - x.min()
        half = math.tan(math.radians(19.47)) * span
        ax.plot([bow, bow - span], [0, half], "k--", lw=0.8)
        ax.plot([bow, bow - span], [0, -half], "k--", lw=0.8, label="Kelvin wedge 19.47 deg")
        ax.legend(loc="upper left", fontsize=8)
    ax.set_aspect("equal")
    ax.set_xlim(x.min(), x.max())
    ax.set_ylim(y.min(), y.max())
    ax.set_xlabel("x / L (flow from right to left)")
    ax.set_ylabel("y / L")
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)
    return out


def plot(directory):
    path = os.path.join(directory, "resistance.h5")
    with h5py.File(path, "r") as f:
        length = 1.0
        fn = scalar(f, "Fn")
        speed = scalar(f, "speed")
        if not math.isnan(fn):
            length = speed * speed / (fn * fn * 9.81)
        title = f"{os.path.basename(os.path.normpath(directory))}: C_T = {scalar(f, 'C_T'):.4e}"
        if not math.isnan(fn):
            title += f", Fn = {fn:.3f}"
        written = []
        if "wave_cuts" in f:
            fig, ax = plt.subplots(figsize=(9, 4))
            for name in sorted(f["wave_cuts"]):
                g = f["wave_cuts"][name]
                x = g["x"][:]
                eta = g["eta"][:]
                ax.plot(x / length, eta / length * 1e3, label=f"y/L = {g.attrs['y'] / length:.3f}")
            ax.set_xlabel("x / L (bow at the right, flow from right to left)")
            ax.set_ylabel("eta / L x 1000")
            ax.set_title(title)
            ax.grid(alpha=0.3)
            ax.legend()
            out = os.path.join(directory, "wave_cuts.png")
            fig.tight_layout()
            fig.savefig(out, dpi=120)
            plt.close(fig)
            written.append(out)
        if "wave_profile" in f:
            x = f["wave_profile/x"][:]
            y = f["wave_profile/y"][:]
            eta = f["wave_profile/eta"][:]
            fig, ax = plt.subplots(figsize=(9, 4))
            for side, mask in (("port (y > 0)", y >= 0), ("starboard (y < 0)", y < 0)):
                if mask.any():
                    ax.plot(x[mask] / length, eta[mask] / length * 1e3, "o-", ms=3, label=side)
            ax.set_xlabel("x / L")
            ax.set_ylabel("eta / L x 1000 at the hull")
            ax.set_title(title)
            ax.grid(alpha=0.3)
            ax.legend()
            out = os.path.join(directory, "wave_profile.png")
            fig.tight_layout()
            fig.savefig(out, dpi=120)
            plt.close(fig)
            written.append(out)
        if "surface" in f:
            out = plot_pattern(f, length, title, os.path.join(directory, "wave_pattern.png"))
            written.append(out)
        h = f["history"][:]
        fig, (a1, a2) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
        for col, name in ((1, "R_T"), (2, "R_F"), (3, "R_P"), (4, "R_WL (separate)")):
            a1.plot(h[:, 0], h[:, col], label=name)
        # The start-up transient (forces of the impulsive start, hundreds of
        # times the steady values) would flatten the plot: scale the axis to
        # the second half of the run.
        late = h[len(h) // 2:, 1:5]
        late = late[np.isfinite(late)]
        if late.size:
            lo, hi = float(late.min()), float(late.max())
            pad = 0.5 * (hi - lo) + 0.05 * max(abs(lo), abs(hi), 1e-12)
            a1.set_ylim(lo - pad, hi + pad)
        release = scalar(f, "release_time")
        if math.isfinite(release):
            for ax in (a1, a2):
                ax.axvline(release, color="0.5", ls=":", lw=1.0)
            a1.annotate("rigid lid released", (release, 1.0), xycoords=("data", "axes fraction"),
                        xytext=(3, -12), textcoords="offset points", fontsize=8, color="0.3")
        a1.set_ylabel("N")
        a1.legend()
        a1.grid(alpha=0.3)
        a1.set_title(title)
        a2.semilogy(h[:, 0], h[:, 5], label="force change / R_T over one window")
        if np.any(np.isfinite(h[:, 6]) & (h[:, 6] > 0)):
            a2.semilogy(h[:, 0], h[:, 6], label="eta change (relative L2)")
        a2.axhline(scalar(f, "tolerance"), color="k", ls="--", lw=0.8, label="tolerance")
        a2.set_xlabel("pseudo-time (s)")
        a2.legend()
        a2.grid(alpha=0.3)
        out = os.path.join(directory, "convergence.png")
        fig.tight_layout()
        fig.savefig(out, dpi=120)
        plt.close(fig)
        written.append(out)
    return written


def main(argv):
    if len(argv) < 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    for directory in argv[1:]:
        if not os.path.isfile(os.path.join(directory, "resistance.h5")):
            print(f"plot_resistance: {directory}/resistance.h5 not found", file=sys.stderr)
            return 1
        for out in plot(directory):
            print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
