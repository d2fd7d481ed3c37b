#!/usr/bin/python3
"""Benchmark: cost of the CFD captive (PMM) runs (issue #7, acceptance 6).

Builds the grid of a CFD captive campaign, runs the whole campaign with
`kelvin captive --jobs N` (or reuses finished runs with --reuse) and reports,
from each run's result.h5 (written by cfd/campaign: process CPU time of the
time steps, largest Courant number, cells):

  - CPU time per PMM period per million cells for every pure sway / pure yaw
    run (target: at most 3 CPU-hours per million cells per period; the
    published LFS solver needed about 12: 34 CPU-h per period on 2.8M cells,
    shared/reference/kcs_conditions.yaml);
  - the largest Courant number met during each run, with its time step;
  - period-to-period change of the first-harmonic amplitudes of Y' and N'
    over the last two periods (periodicity after the ramp-up);
  - the wall time of the whole campaign on this machine.

Usage: tools/bench/pmm_cost_bench.py --kelvin build/release/tools/kelvin
       [--campaign data/cases/captive_cfd/wigley_lfs_campaign.yaml]
       [--mesh data/cases/captive_cfd/wigley_lfs_mesh.yaml] [--jobs 2] [--reuse] [--write]
"""
import argparse
import datetime
import math
import re
import os
import subprocess
import sys
import time

import h5py
import numpy as np
import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pimple_vs_openfoam import replace_section  # noqa: E402

NAME = "pmm_cost"
TARGET = 3.0         # CPU-h per million cells per period
PUBLISHED = 34.0 / 2.8  # CPU-h per million cells per period of the published LFS solver


def first_harmonic(t, y, omega):
    """Amplitude of the first harmonic of y(t) over whole periods (least squares)."""
    a = np.column_stack([np.ones_like(t), np.sin(omega * t), np.cos(omega * t)])
    c, *_ = np.linalg.lstsq(a, y, rcond=None)
    return math.hypot(c[1], c[2])


def analyse_run(d, steps_per_period):
    with h5py.File(os.path.join(d, "result.h5"), "r") as f:
        attrs = dict(f.attrs)
        if "cpu_seconds" not in attrs:
            raise SystemExit(f"{d}/result.h5 has no cost attributes (written by an older kelvin): rerun the campaign")
        t = f["captive/time"][()]
        yp, npr = f["captive/Y_prime"][()], f["captive/N_prime"][()]
    steps = int(attrs["steps"])
    r = dict(name=os.path.basename(d), cells=int(attrs["cells"]), steps=steps, cpu=float(attrs["cpu_seconds"]),
             courant=float(attrs["courant_max"]), dt=float(t[1] - t[0]) if len(t) > 1 else float("nan"))
    if steps_per_period:
        periods = steps / steps_per_period
        r["periods"] = periods
        r["cpu_h_per_period_per_mcell"] = r["cpu"] / 3600.0 / periods / (r["cells"] / 1e6)
        n = steps_per_period
        omega = 2 * math.pi / (n * r["dt"])
        change = []
        for ch in (yp, npr):
            last = first_harmonic(t[-n:], ch[-n:], omega)
            before = first_harmonic(t[-2 * n:-n], ch[-2 * n:-n], omega)
            change.append(abs(last - before) / last if last > 0 else float("nan"))
        r["period_change"] = max(change)
    return r


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kelvin", required=True, help="the kelvin program (release build)")
    ap.add_argument("--campaign", default="data/cases/captive_cfd/wigley_lfs_campaign.yaml")
    ap.add_argument("--mesh", default="data/cases/captive_cfd/wigley_lfs_mesh.yaml")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--reuse", action="store_true", help="keep finished runs (the campaign wall time is then not measured)")
    ap.add_argument("--time-log", help="with --reuse: the `/usr/bin/time -v` output of the `kelvin captive` run that "
                    "computed the reused runs (its wall and CPU times are reported)")
    ap.add_argument("--write", action="store_true", help="write the section into BENCHMARKS.md")
    ap.add_argument("--output", default="BENCHMARKS.md")
    args = ap.parse_args()

    with open(args.campaign) as f:
        campaign = yaml.safe_load(f)
    cfd = campaign["cfd"]
    run_dir = os.path.normpath(os.path.join(os.path.dirname(args.campaign), cfd["directory"]))
    steps_per_period = int(cfd.get("steps_per_period", 80))
    omega_prime = float(campaign.get("tests", {}).get("omega_prime", 3.0))
    env = dict(os.environ, OMPI_MCA_ess_singleton_isolated="1")
    subprocess.run([args.kelvin, "mesh", args.mesh], check=True, env=env, stdout=subprocess.DEVNULL)
    wall = None
    if not args.reuse and os.path.isdir(run_dir):
        raise SystemExit(f"{run_dir} exists: remove it for a timed campaign, or pass --reuse")
    load = os.getloadavg()[0]
    start = time.monotonic()
    subprocess.run([args.kelvin, "captive", args.campaign, "--jobs", str(args.jobs), "--no-progress"], check=True,
                   env=env)
    if not args.reuse:
        wall = time.monotonic() - start

    runs = []
    for name in sorted(os.listdir(run_dir)):
        d = os.path.join(run_dir, name)
        if not os.path.exists(os.path.join(d, "result.h5")):
            continue
        harmonic = name.startswith(("sway", "yaw"))
        runs.append(analyse_run(d, steps_per_period if harmonic else 0))
    pmm = [r for r in runs if "periods" in r]
    if not pmm:
        raise SystemExit(f"no finished pure sway / pure yaw run under {run_dir}")
    worst = max(r["cpu_h_per_period_per_mcell"] for r in pmm)
    met = worst <= TARGET

    rows = "\n".join(
        f"| {r['name']} | {r['cells']:,} | {r['steps']} | {r.get('periods', 0):.0f} | {r['cpu']:.0f} s | "
        + (f"**{r['cpu_h_per_period_per_mcell']:.2f}** | {100 * r['period_change']:.3f}% |" if "periods" in r
           else "steady | - |")
        + f" {r['dt']:.4g} s | {r['courant']:.3g} |" for r in runs)
    total_cpu = sum(r["cpu"] for r in runs)
    cpu_name = subprocess.run(["bash", "-c", "grep -m1 'model name' /proc/cpuinfo | cut -d: -f2"],
                              capture_output=True, text=True).stdout.strip()
    if wall is None and args.time_log:
        log = open(args.time_log).read()
        m = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([0-9:.]+)", log)
        u = re.search(r"User time \(seconds\): ([0-9.]+)", log)
        share = re.search(r"Percent of CPU this job got: ([0-9]+)%", log)
        if not (m and u):
            raise SystemExit(f"{args.time_log}: no `/usr/bin/time -v` wall/user lines")
        parts = [float(x) for x in m.group(1).split(":")]
        elapsed = sum(v * 60 ** (len(parts) - 1 - i) for i, v in enumerate(parts))
        wall_text = (f"{elapsed / 60:.1f} min (from `{args.time_log}`: `/usr/bin/time -v` of the `kelvin captive "
                     f"--jobs {args.jobs}` run that computed these results; {float(u.group(1)) / 60:.1f} CPU-min user "
                     f"time, {share.group(1) if share else '?'}% of one core on average while other jobs shared the "
                     f"machine)")
    elif wall is not None:
        wall_text = (f"{wall / 60:.1f} min with `--jobs {args.jobs}` ({len(runs)} runs, {total_cpu / 60:.1f} CPU-min "
                 f"in the time steps; 1-minute load average {load:.1f} at the start on 2 cores)"
                 )
    else:
        wall_text = "not measured (finished runs reused)"
    text = f"""
## CFD captive (PMM) cost per period per million cells

Run by `tools/bench/pmm_cost_bench.py` on {datetime.datetime.utcnow():%Y-%m-%d %H:%M} UTC, {cpu_name}, 2 cores.
Campaign `{args.campaign}` on the grid of `{args.mesh}`: k-omega SST with wall functions, the linearized free
surface on the moving mesh, the whole grid moving with the hull; PMM at omega' = omega L / U = {omega_prime:g},
{steps_per_period} time steps per PMM period.
CPU time is the process CPU time of the time steps of each run (`result.h5` attributes written by the campaign).
The reference is the published LFS solver's cost, {PUBLISHED:.1f} CPU-h per million cells per period (34 CPU-h per
period on 2.8M cells, KCS pure sway), and the target is at most {TARGET:g}.

| run | cells | steps | periods | CPU | CPU-h / period / Mcell | period-to-period change (Y', N' 1st harmonic) | dt | max Courant |
| --- | --- | --- | --- | --- | --- | --- | --- | --- |
{rows}

Worst PMM run: {worst:.2f} CPU-h per million cells per period, {worst / PUBLISHED:.2f} of the published solver's
cost: target {'met' if met else 'NOT met'}. Whole campaign wall time: {wall_text}.
Periodicity (issue #7 acceptance 4 asks for < 1% change from one period to the next after the ramp):
{', '.join(f"{r['name']} {100 * r['period_change']:.3f}%" for r in pmm)}; largest {100 * max(r['period_change'] for r in pmm):.3f}%
({'met' if max(r['period_change'] for r in pmm) < 0.01 else 'NOT met'}).
"""
    print(text)
    if args.write:
        replace_section(args.output, NAME, text)
        print(f"wrote the {NAME} section of {args.output}")


if __name__ == "__main__":
    main()
