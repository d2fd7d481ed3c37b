#!/usr/bin/python3
"""Benchmark: kelvin's PIMPLE cost per cell, two kelvin binaries side by side.

The lid-driven cube of pimple_vs_openfoam.py (blockMesh grid, laminar,
2 outer x 2 pressure correctors, AMG setup every step) run alternately by a
"before" and an "after" binary in the same session, so that a change to the
solver or the run layer is judged by the ratio of their CPU time per outer
iteration per cell (the first step excluded, as in the PIMPLE benchmark),
not by timings of different days. Prints the per-run figures, the medians
and their ratio; with --write, the section `pimple_before_after` of
BENCHMARKS.md.

Usage: tools/bench/pimple_before_after.py --before OLD/kelvin --after build/ci/tools/kelvin
       [--cells 80] [--steps 6] [--rounds 4] [--label "the change"] [--write]
"""
import argparse
import datetime
import os
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pimple_vs_openfoam as peer  # noqa: E402

NAME = "pimple_before_after"


def cost_per_cell(kelvin, case, out, cells):
    """CPU time per outer iteration per cell (us) of one run, first step excluded."""
    env = dict(os.environ, OMPI_MCA_ess_singleton_isolated="1")
    subprocess.run([kelvin, "run", "--no-progress", "-o", out, case], env=env, check=True, capture_output=True)
    cpu = peer.h5_column(os.path.join(out, "history.h5"), "/cpu_time")
    outer = peer.h5_column(os.path.join(out, "history.h5"), "/outer_iterations")
    return (cpu[-1] - cpu[0]) / sum(outer[1:]) / cells * 1e6


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--before", required=True, help="the kelvin program before the change")
    ap.add_argument("--after", required=True, help="the kelvin program after the change")
    ap.add_argument("--cells", type=int, default=80, help="cells per side (default 80: 512,000 cells)")
    ap.add_argument("--steps", type=int, default=6)
    ap.add_argument("--rounds", type=int, default=4, help="runs of each binary, alternating which goes first")
    ap.add_argument("--label", default="the change", help="what the two binaries differ by")
    ap.add_argument("--write", action="store_true")
    ap.add_argument("--output", default="BENCHMARKS.md")
    args = ap.parse_args()
    n = args.cells
    work = tempfile.mkdtemp(prefix="kelvin_pimple_ab_")
    nu, dt = 0.01, 0.4 / n  # Re 100, Courant 0.4
    peer.foam_case(os.path.join(work, "openfoam"), n, args.steps, dt, nu)
    peer.foam(os.path.join(work, "openfoam"), "blockMesh", os.path.join(work, "blockMesh.log"))
    case = os.path.join(work, "case.yaml")
    peer.kelvin_case(case, os.path.join(work, "openfoam", "constant", "polyMesh"), args.steps, dt, nu,
                     os.path.join(work, "out"), True)
    runs = {"before": [], "after": []}
    for r in range(args.rounds):
        for k in (("before", "after") if r % 2 == 0 else ("after", "before")):
            runs[k].append(cost_per_cell(getattr(args, k), case, os.path.join(work, "out_" + k), n ** 3))
    med = {k: statistics.median(v) for k, v in runs.items()}
    load = os.getloadavg()[0]
    lines = [f"## PIMPLE cost per cell, before and after {args.label}", "",
             f"Run by `tools/bench/pimple_before_after.py` on {datetime.datetime.utcnow():%Y-%m-%d %H:%M} UTC: the "
             f"lid-driven cube of the PIMPLE benchmark ({n}^3 = {n ** 3:,} cells, {args.steps} steps, AMG setup every "
             f"step), {args.rounds} runs of each binary alternating, one at a time; process CPU time per outer "
             f"iteration per cell, first step excluded. 1-minute load average at the end {load:.1f} on 2 cores.", "",
             "| binary | runs (us per cell per outer iteration) | median |", "| --- | --- | --- |"]
    for k in ("before", "after"):
        lines.append(f"| {k} | {', '.join(f'{x:.3f}' for x in runs[k])} | {med[k]:.3f} |")
    ratio = med["after"] / med["before"]
    lines += ["", f"after / before: {ratio:.3f} (target <= 1.03: {'met' if ratio <= 1.03 else '**missed**'})."]
    text = "\n".join(lines) + "\n"
    print(text)
    if args.write:
        peer.replace_section(args.output, NAME, text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
