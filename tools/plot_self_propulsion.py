#!/usr/bin/python3
"""Self-propulsion report of a free-running run with a body-force propeller
(`kelvin run` with motion: {kind: free} and a propeller: section; the layout
is data/schema/self_propulsion_schema.md).

Usage: tools/plot_self_propulsion.py RESULT_DIR

Reads RESULT_DIR/history.h5 and writes RESULT_DIR/self_propulsion.png: three
panels against time, the propeller rate n, the thrust T with the hull's
resistance -X_hull, and the carriage force X_c on the held surge. The
averaging window of the self-propulsion point (the last self_propulsion/window
seconds) is shaded, and the title gives the point when the file has it.
"""
import math
import os
import sys
import tempfile

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# The per-step datasets the plot needs: (name, columns it must have).
REQUIRED = (("time", 1), ("propeller/state", 3), ("body/hull_load", 3), ("body/constraint_load", 3))
POINT = ("n", "thrust", "K_T", "K_Q", "J", "thrust_deduction", "wake_fraction", "window")


def fail(message):
    sys.exit(f"plot_self_propulsion: {message}")


def read(path):
    """The per-step series and the self_propulsion/ point (empty if absent)."""
    if not os.path.exists(path):
        fail(f"{path} not found (expected the history.h5 of a `kelvin run` with a propeller: section)")
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        fail(f"{path}: not an HDF5 file ({e})")
    with f:
        series = {}
        for name, columns in REQUIRED:
            if name not in f or not isinstance(f[name], h5py.Dataset):
                fail(f"{path}: no dataset '{name}'; not the history of a self-propulsion run "
                     "(motion: {kind: free} with a propeller: section)")
            data = f[name][()]
            width = 1 if data.ndim == 1 else data.shape[1]
            if width != columns:
                fail(f"{path}: dataset '{name}' has {width} columns; expected {columns}")
            series[name] = data
        rows = {len(v) for v in series.values()}
        if len(rows) != 1 or rows == {0}:
            fail(f"{path}: the datasets {', '.join(n for n, _ in REQUIRED)} have different or no rows "
                 f"({', '.join(str(len(series[n])) for n, _ in REQUIRED)})")
        point = {}
        if "self_propulsion" in f:
            for name in POINT:
                key = f"self_propulsion/{name}"
                if key not in f:
                    fail(f"{path}: group 'self_propulsion' has no dataset '{name}'")
                point[name] = float(f[key][0])
    return series, point


def late_limits(t, values, start):
    """Axis limits from the samples after `start` when the whole run spans
    more than four times their range (the first steps of an impulsive start
    carry forces many times the settled ones and would flatten the rest), or
    None to autoscale."""
    late = np.concatenate([v[t >= start] for v in values])
    late = late[np.isfinite(late)]
    everything = np.concatenate(values)
    everything = everything[np.isfinite(everything)]
    if late.size == 0 or everything.size == 0:
        return None
    lo, hi = float(late.min()), float(late.max())
    span = max(hi - lo, 0.02 * max(abs(lo), abs(hi)), 1e-12)
    if float(everything.max() - everything.min()) <= 4.0 * span:
        return None
    return lo - 0.1 * span, hi + 0.1 * span


def title_of(directory, point):
    name = os.path.basename(os.path.normpath(directory))
    if not point:
        return f"{name}: no self_propulsion/ point (fixed rate, or the run ended before self_propulsion.start_time)"
    t = point["thrust_deduction"]
    t_text = f"t {t:.4f}" if math.isfinite(t) else "t n/a (no towed_resistance)"
    return (f"{name}: self-propulsion point over the last {point['window']:.3g} s\n"
            f"n {point['n']:.4g} 1/s, T {point['thrust']:.4g} N, K_T {point['K_T']:.4f}, "
            f"10K_Q {10 * point['K_Q']:.4f}, J {point['J']:.4f}, {t_text}, w_T {point['wake_fraction']:.4f}")


def plot(directory):
    path = os.path.join(directory, "history.h5")
    series, point = read(path)
    t = series["time"]
    n = series["propeller/state"][:, 0]
    thrust = series["propeller/state"][:, 1]
    resistance = -series["body/hull_load"][:, 0]
    carriage = series["body/constraint_load"][:, 0]

    fig, (a1, a2, a3) = plt.subplots(3, 1, figsize=(9, 8), sharex=True)
    a1.plot(t, n, color="C0", label="n")
    a1.set_ylabel("n (1/s)")
    a2.plot(t, thrust, color="C1", label="thrust T")
    a2.plot(t, resistance, color="C2", label="hull resistance -X_hull")
    a2.set_ylabel("N")
    a3.plot(t, carriage, color="C3", label="carriage force X_c")
    a3.axhline(0.0, color="k", lw=0.6)
    a3.set_ylabel("N")
    a3.set_xlabel("t (s)")

    if point and point["window"] > 0:
        begin = t[-1] - point["window"]
        for ax in (a2, a3):
            ax.axvspan(begin, t[-1], color="0.88", zorder=0)
        a1.axvspan(begin, t[-1], color="0.88", zorder=0, label=f"averaging window ({point['window']:.3g} s)")
        a1.hlines(point["n"], begin, t[-1], colors="k", linestyles="--", lw=0.8, label="mean n")
        a2.hlines(point["thrust"], begin, t[-1], colors="k", linestyles="--", lw=0.8, label="mean T")

    # The force panels are scaled to the run after its first tenth when the
    # start-up is far off that scale (the panel says so); n is not (its ramp
    # from 0 is part of the story).
    start = t[0] + 0.1 * (t[-1] - t[0])
    for ax, values in ((a1, [n]), (a2, [thrust, resistance]), (a3, [carriage])):
        limits = late_limits(t, values, start) if ax is not a1 else None
        if limits:
            ax.set_ylim(*limits)
            finite = np.concatenate(values)
            finite = finite[np.isfinite(finite)]
            peak = float(finite[np.argmax(np.abs(finite))])
            ax.annotate(f"axis scaled to t > {start:.3g} s (start-up peak {peak:.3g} N off scale)", (0.0, 1.0),
                        xycoords="axes fraction", xytext=(4, -12), textcoords="offset points", fontsize=7,
                        color="0.3")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="best")
    a1.set_title(title_of(directory, point), fontsize=9)
    fig.tight_layout()

    out = os.path.join(directory, "self_propulsion.png")
    # Atomic: a reader never sees a half-written PNG.
    handle, tmp = tempfile.mkstemp(prefix=".self_propulsion.", suffix=".png", dir=directory)
    os.close(handle)
    try:
        fig.savefig(tmp, dpi=120)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes the file private
        os.replace(tmp, out)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    finally:
        plt.close(fig)
    return out, len(t)


def main(argv):
    if len(argv) != 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    out, steps = plot(argv[1])
    print(f"wrote {out} ({steps} steps)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
