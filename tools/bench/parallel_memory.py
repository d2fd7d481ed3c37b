#!/usr/bin/env python3
"""Benchmark: kelvin's memory per cell on 2 MPI ranks against 1 (issue 23,
acceptance 3: per-cell memory within 10% of serial).

Each process carries a fixed cost (MPI, PETSc, hypre and their buffers,
about 40 MB) that says nothing about how the solver scales with the mesh, so
the figure is the marginal memory per cell: the lid-driven cube of
tools/bench/parallel_speedup.py at two sizes (blockMesh, --small and --large
cells per side), run by tools/bench/parallel_bench serially and on 2 ranks,
and the difference between the sizes over the cells added (summed over the
ranks). parallel_bench reports malloc's live heap after the mesh, after
building the solver and after the steps, and the peak resident size
(getrusage); the table gives each stage's increment and their ratio. With
--kelvin, the whole program is measured the same way: `kelvin run` of the
same cubes (2 steps and the field output at the last), serially and under
mpiexec -np 2, each process's peak resident size.

Usage: tools/bench/parallel_memory.py --bench build/ci/tools/bench/parallel_bench [--kelvin build/ci/tools/kelvin] [--small 40] [--large 72] [--write BENCHMARKS.md]
"""
import argparse
import datetime
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pimple_vs_openfoam import foam_case, foam, write_or_print  # noqa: E402

MPI = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-np"]


def kelvin(bench, poly_mesh, ranks, steps, dt, nu):
    """One parallel_bench run (the triad without a mesh), serially or on `ranks` ranks: its JSON report."""
    cmd = [bench, poly_mesh, "--steps", str(steps), "--dt", str(dt), "--nu", str(nu)] if poly_mesh else [bench, "--triad"]
    env = dict(os.environ)
    if ranks == 1:
        env["OMPI_MCA_ess_singleton_isolated"] = "1"
    else:
        cmd = MPI + [str(ranks)] + cmd
    out = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if out.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed:\n{out.stderr[-3000:]}")
    return json.loads([line for line in out.stdout.splitlines() if line.startswith("{")][-1])


NAME = "parallel_memory"
STAGES = [("live_mesh_mb", "the mesh (a rank's local mesh, its ghost cells and `DomainPart` maps)"),
          ("live_solver_mb", "building the solver (fields, gradients, matrix structure)"),
          ("live_end_mb", "the steps (linear solvers' own storage)")]


def cube(work, n, steps, dt, nu):
    d = os.path.join(work, f"cube{n}")
    foam_case(d, n, steps, dt, nu)
    foam(d, "blockMesh", os.path.join(work, f"blockMesh{n}.log"))
    return os.path.join(d, "constant", "polyMesh")


CASE = """mesh: {{poly_mesh: {mesh}}}
physics: {{nu: {nu}}}
schemes: {{convection: linear_upwind}}
solution:
  n_outer: 2
  n_correctors: 2
  momentum: {{solver: bicgstab, relative_tolerance: 1.0e-6}}
  pressure: {{solver: pcg_amg, relative_tolerance: 1.0e-2}}
time: {{dt: {dt}, end: {end}}}
boundary:
  lid: {{U: {{type: fixedValue, value: [1, 0, 0]}}, p: {{type: zeroGradient}}}}
  walls: {{U: {{type: noSlip}}, p: {{type: zeroGradient}}}}
output: {{directory: out, vtu_interval: 0}}
"""
# Runs a program and prints the peak resident size of it (KB), as a rank's wrapper.
PEAK = "import resource, subprocess, sys; r = subprocess.run(sys.argv[1:]); " \
       "print('peak_kb', resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss); sys.exit(r.returncode)"


def kelvin_run(program, work, mesh, ranks, steps, dt, nu):
    """Peak resident MB of each process of `kelvin run` on the cube."""
    d = os.path.join(work, f"run_{os.path.basename(os.path.dirname(os.path.dirname(mesh)))}_{ranks}")
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, "case.yaml"), "w") as f:
        f.write(CASE.format(mesh=mesh, nu=nu, dt=dt, end=steps * dt))
    cmd = [sys.executable, "-c", PEAK, os.path.abspath(program), "run", "case.yaml", "--no-progress"]
    env = dict(os.environ)
    if ranks == 1:
        env["OMPI_MCA_ess_singleton_isolated"] = "1"
    else:
        cmd = MPI + [str(ranks)] + cmd
    out = subprocess.run(cmd, cwd=d, capture_output=True, text=True, env=env)
    if out.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed in {d}:\n{out.stdout[-2000:]}{out.stderr[-2000:]}")
    return [int(line.split()[1]) / 1024.0 for line in out.stdout.splitlines() if line.startswith("peak_kb")]


def marginal(small, large, key):
    """Bytes per cell added between the two sizes, summed over the ranks."""
    return (sum(large[key]) - sum(small[key])) * 2**20 / (large["cells"] - small["cells"])


def table(runs):
    """Rows (stage, serial B/cell, 2 ranks B/cell) from runs[ranks] = (small, large)."""
    rows, before = [], {1: 0.0, 2: 0.0}
    for key, label in STAGES:
        now = {r: marginal(*runs[r], key) for r in (1, 2)}
        rows.append((label, now[1] - before[1], now[2] - before[2]))
        before = now
    rows.append(("total live heap after the steps", before[1], before[2]))
    rows.append(("peak resident", marginal(*runs[1], "rss_mb"), marginal(*runs[2], "rss_mb")))
    return rows


def measure(bench, program, work, small, large, steps, nu=0.01):
    """parallel_bench runs (runs[ranks] = [small, large]) and, with `program`, the peak MB of each process
    of `kelvin run` (whole[ranks] = [small, large]), serially and on 2 ranks."""
    runs = {1: [], 2: []}
    whole = {1: [], 2: []}
    for n in (small, large):
        dt = 0.4 / n
        mesh = cube(work, n, steps, dt, nu)
        for ranks in (1, 2):
            runs[ranks].append(kelvin(bench, mesh, ranks, steps, dt, nu))
            if program:
                whole[ranks].append(kelvin_run(program, work, mesh, ranks, steps, dt, nu))
    return runs, whole


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bench", required=True, help="the parallel_bench program")
    ap.add_argument("--kelvin", help="the kelvin program: measure `kelvin run` as well")
    ap.add_argument("--small", type=int, default=40, help="cells per side of the small cube (default 40)")
    ap.add_argument("--large", type=int, default=72, help="cells per side of the large cube (default 72)")
    ap.add_argument("--steps", type=int, default=2)
    ap.add_argument("--work", default=None)
    ap.add_argument("--write", help="BENCHMARKS.md to update (default: print the section)")
    args = ap.parse_args()
    if args.large <= args.small:
        sys.exit(f"--large {args.large}: expected more cells per side than --small {args.small}")
    work = args.work or tempfile.mkdtemp(prefix="kelvin_parallel_memory_")
    runs, whole = measure(args.bench, args.kelvin, work, args.small, args.large, args.steps)
    rows = table(runs)
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    small, large = runs[1][0]["cells"], runs[1][1]["cells"]
    lines = [f"## {NAME}: memory per cell on 2 MPI ranks against 1 (issue 23, acceptance 3)", "",
             f"Run by `tools/bench/parallel_memory.py` on {date}: the lid-driven cube of `parallel_speedup` at "
             f"{small:,} and {large:,} cells ({args.steps} steps each), `parallel_bench` serially and on 2 ranks. "
             "Marginal memory per cell: the difference between the two sizes over the cells added, summed over the "
             "ranks (the fixed cost of a process, its libraries and buffers, drops out). Live heap is malloc's bytes "
             "in use at the end of each stage; peak resident is getrusage's maximum.", "",
             "| stage | serial (B/cell) | 2 ranks (B/cell) | extra on ranks |", "| --- | ---: | ---: | ---: |"]
    for label, one, two in rows[:-2]:
        lines.append(f"| {label} | {one:,.0f} | {two:,.0f} | {two - one:+,.0f} |")
    for label, one, two in rows[-2:]:
        lines.append(f"| {label} | {one:,.0f} | {two:,.0f} | ratio **{two / one:.3f}** |")
    fixed = [sum(r[0]["rss_mb"]) - marginal(*r, "rss_mb") * r[0]["cells"] / 2**20 for r in (runs[1], runs[2])]
    lines += ["", f"Fixed cost (peak resident at zero cells by the same line): {fixed[0]:.0f} MB serially, "
              f"{fixed[1]:.0f} MB over the 2 ranks. The target of issue 23 is per-cell memory within 10% of serial "
              "(ratio 1.10 or less)."]
    if args.kelvin:
        added = large - small
        per = {r: (sum(whole[r][1]) - sum(whole[r][0])) * 2**20 / added for r in (1, 2)}
        lines += ["", f"`kelvin run` of the same cubes ({args.steps} steps, the field output at the last; on ranks each "
                  "rank writes its piece), peak resident size of each process: "
                  f"serially {whole[1][0][0]:.0f} and {whole[1][1][0]:.0f} MB, on 2 ranks "
                  f"{' + '.join(f'{v:.0f}' for v in whole[2][0])} and {' + '.join(f'{v:.0f}' for v in whole[2][1])} MB: "
                  f"marginal {per[1]:,.0f} B/cell serially, {per[2]:,.0f} summed over the ranks, ratio "
                  f"**{per[2] / per[1]:.3f}**."]
    write_or_print(args.write, NAME, "\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
