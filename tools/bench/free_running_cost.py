#!/usr/bin/python3
"""Benchmark: free-running CFD, section `free_running_cost` of BENCHMARKS.md.

Runs (`--jobs N` at a time, one core each; the CPU is each run's own time
loop from history.h5, so parallel runs compare) `kelvin run` on
  - data/cases/free_running/dtc_towed.yaml            (the resistance run),
  - data/cases/free_running/dtc_self_propulsion.yaml  (model point, F_D = 0),
  - data/cases/free_running/dtc_self_propulsion_ship.yaml (ship point, F_D = 13.947 N),
  - data/cases/free_running/wigley_self_propulsion.yaml,
all on the grids their files name (build the DTC grid first with
`kelvin mesh data/cases/mesh/dtc_snappy.yaml --family 3 -o build/grids/doublebody_dtc`
(grid 1), the Wigley grid with
`kelvin mesh data/cases/captive_cfd/wigley_quick_mesh.yaml`), and tabulates
  - the self-propulsion points (n, T, Q, K_T, 10 K_Q, J, t, w_T) from each
    history.h5 `self_propulsion/` group, the towed R_T and the grid's friction
    against ITTC-57;
  - the cost: the CPU of the self-propulsion run against the resistance run of
    the same hull and grid (target at most 2), and CPU-hours per million cells
    per simulated second, beside the published LFS figure (295 CPU-h on 2.7M
    cells for the KCS self-propulsion; shared/reference/kcs_conditions.yaml).

Usage: tools/bench/free_running_cost.py --kelvin build/ci/tools/kelvin [--jobs 2] [--reuse] [--write BENCHMARKS.md]
"""
import argparse
import os
import re
import subprocess
import sys
import time

import h5py
import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doublebody_study import cells_of, ittc57  # noqa: E402
from pimple_vs_openfoam import write_or_print  # noqa: E402

NAME = "free_running_cost"
ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
CASES = os.path.join(ROOT, "data", "cases", "free_running")
RESULTS = os.path.join(ROOT, "results", "free_running")
RHO, U, S, L, NU = 998.8, 1.668, 6.2428, 5.976, 1.09e-6  # the DTC model (data/ships/dtc.yaml)


def case_file(case):
    return os.path.join(CASES, case + ".yaml")


def results_dir(case):
    return os.path.join(RESULTS, case)


def launch(kelvin, case):
    """Starts `kelvin run` on one case; its output goes to <results>/kelvin_run.log."""
    os.makedirs(results_dir(case), exist_ok=True)
    env = dict(os.environ, OMPI_MCA_ess_singleton_isolated="1")
    with open(os.path.join(results_dir(case), "kelvin_run.log"), "w") as log:
        return subprocess.Popen([kelvin, "run", case_file(case), "--no-progress"], env=env, stdout=log,
                                stderr=subprocess.STDOUT)


def run_all(kelvin, cases, jobs):
    """Runs the cases, `jobs` at a time; stops on the first failure."""
    pending, running = list(cases), {}
    while pending or running:
        while pending and len(running) < jobs:
            case = pending.pop(0)
            running[case] = launch(kelvin, case)
        finished = [c for c, p in running.items() if p.poll() is not None]
        if not finished:
            time.sleep(2.0)
            continue
        case = finished[0]
        proc = running.pop(case)
        if proc.returncode != 0:
            for p in running.values():
                p.kill()
            sys.exit(f"{case}: kelvin run failed (exit {proc.returncode}); see "
                     f"{os.path.join(results_dir(case), 'kelvin_run.log')}")
        print(f"{case}: done", file=sys.stderr)


def history(case):
    """The run's history; CPU is the time loop's own (history cpu_time), so runs in parallel compare."""
    with h5py.File(os.path.join(results_dir(case), "history.h5"), "r") as f:
        h = {"time": f["time"][:], "cpu": float(f["cpu_time"][-1]), "hull": f["body/hull_load"][:],
             "viscous": f["forces/hull/viscous"][:], "settled": bool(f["steady/converged"][0]) if "steady" in f else None}
        if "self_propulsion" in f:
            h["point"] = {k: float(f["self_propulsion"][k][0]) for k in f["self_propulsion"]}
    return h


def settled_text(settled):
    """The steady column: met, not met by time.end, or no steady criterion in the case."""
    if settled is None:
        return "none set"
    return "met" if settled else "NOT met (time.end)"


def run_log(case):
    with open(os.path.join(results_dir(case), "kelvin_run.log")) as f:
        return f.read()


def case_settings(case, log):
    """The case's grid (polyMesh path), its cell count and F_D (motion.external_load.X); refuses a run
    whose log names another cell count (a stale result under --reuse)."""
    with open(case_file(case)) as f:
        c = yaml.safe_load(f)
    mesh = os.path.normpath(os.path.join(CASES, c["mesh"]["poly_mesh"]))
    cells = cells_of(mesh)
    m = re.search(r"^cells (\d+)", log, re.M)
    if not m or int(m.group(1)) != cells:
        sys.exit(f"{results_dir(case)}/kelvin_run.log: the run's mesh has "
                 f"{m.group(1) if m else 'an unknown number of'} cells, {case_file(case)} names a mesh of "
                 f"{cells}: re-run without --reuse")
    F_D = float(c["motion"].get("external_load", {}).get("X", 0.0))
    return os.path.relpath(mesh, ROOT), cells, F_D


def average_time():
    """The self-propulsion point's averaging window (propeller.self_propulsion.average_time, s); the towed
    loads are averaged over the same window."""
    with open(case_file("dtc_self_propulsion")) as f:
        return float(yaml.safe_load(f)["propeller"]["self_propulsion"]["average_time"])


def wall_span(case):
    """(start, end) of the run in wall-clock seconds: the birth and last change of its log (Linux statx)."""
    out = subprocess.run(["stat", "-c", "%W %Y", os.path.join(results_dir(case), "kelvin_run.log")],
                         capture_output=True, text=True, check=True).stdout.split()
    return float(out[0]), float(out[1])


def alone_share(case, others):
    """The share of the run's wall time during which none of the other runs was running (None: unknown)."""
    start, end = wall_span(case)
    if start <= 0 or end <= start:
        return None
    busy = [(max(start, s), min(end, e)) for s, e in (wall_span(o) for o in others) if s > 0]
    busy = sorted((a, b) for a, b in busy if b > a)
    covered, reach = 0.0, start
    for a, b in busy:
        covered += max(0.0, b - max(a, reach))
        reach = max(reach, b)
    return 1.0 - covered / (end - start)


def disk_cells_across(log):
    """The disk's cells across from kelvin's warning in the run log; None: it did not warn (10 or more)."""
    m = re.search(r"only ([0-9.]+) cells across the disk diameter", log)
    return float(m.group(1)) if m else None


def tail_mean_X(h, seconds):
    """Means of the hull's X and of its viscous part over the last `seconds` of the run (X oscillates)."""
    t = h["time"]
    keep = t >= t[-1] - seconds
    return float(h["hull"][keep, 0].mean()), float(h["viscous"][keep, 0].mean())


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kelvin", help="the kelvin program (not needed with --reuse)")
    ap.add_argument("--jobs", type=int, default=1, help="runs at a time (CPU is each run's own)")
    ap.add_argument("--reuse", action="store_true", help="tabulate the finished runs in results/ without running")
    ap.add_argument("--write", help="replace the section in this file (e.g. BENCHMARKS.md)")
    a = ap.parse_args()

    names = ["dtc_towed", "dtc_self_propulsion", "dtc_self_propulsion_ship", "wigley_self_propulsion"]
    if not a.reuse:
        if not a.kelvin:
            ap.error("--kelvin is needed unless --reuse")
        run_all(a.kelvin, names, a.jobs)
    runs = {}
    for case in names:
        log = run_log(case)
        grid, cells, F_D = case_settings(case, log)
        runs[case] = {"h": history(case), "cells": cells, "grid": grid, "F_D": F_D, "log": log}
        runs[case]["cpu"] = runs[case]["h"]["cpu"]

    towed = runs["dtc_towed"]["h"]
    AVERAGE = average_time()
    X_mean, Xv_mean = tail_mean_X(towed, AVERAGE)
    R_T, R_F = -X_mean, -Xv_mean
    R_F0 = ittc57(U * L / NU) * 0.5 * RHO * S * U * U
    across = disk_cells_across(runs["dtc_self_propulsion"]["log"])
    if across is not None:
        disk = f"its disk is {across:.1f} cells across (kelvin warns below 10)"
    else:
        disk = "its disk is at least 10 cells across"
    friction_ok = 0.97 <= R_F / R_F0 <= 1.07
    short = R_T < 0.95 * 31.83
    resistance = (f"R_T is {100 * (R_T / 31.83 - 1):+.0f}% off the measurement"
                  + (" with the friction within 0.97-1.07 of ITTC-57" if friction_ok else "") + "; "
                  f"the pressure part R_T - R_F is {R_T - R_F:.2f} N"
                  + (" (the low wave part of the uniform-stream free-surface condition over the stern is issue "
                     "#22's), so the propeller here works against a low resistance" if short else "") + ". ")
    lines = [
        "## Free running: self-propulsion and its cost\n",
        "Produced by `tools/bench/free_running_cost.py` (release build, one core per run, runs side by side "
        "where the table below says so; CPU is each run's time loop). "
        "The hulls are towed at constant speed in the earth frame (surge held, the CFD form of a self-propulsion "
        "test) with the body-force propeller of their ship files, the rate controlled until the carriage force "
        "vanishes (`data/cases/free_running/`). The DTC propeller and open-water table are those of the "
        "OpenFOAM-dev DTCHullProp tutorial; the Wigley's propeller is assumed (data/ships/wigley.yaml).\n",
        f"DTC grid `{runs['dtc_towed']['grid']}` ({runs['dtc_towed']['cells']} cells): towed R_T = {R_T:.3f} N "
        f"(measured 31.83 N, el Moctar et al. 2012), R_F = {R_F:.2f} N = **{R_F / R_F0:.3f} of ITTC-57** "
        f"({R_F0:.2f} N), both means over the last {AVERAGE:g} s; {disk}. " + resistance +
        "The thrust deduction t = 1 - (R_T - F_D) / T uses this R_T.\n",
        "| run | n (1/s) | T (N) | Q (N m) | K_T | 10 K_Q | J (disk) | t | w_T | carriage force left (N) | steps | "
        "steady criterion |",
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |",
    ]
    for case in names[1:]:
        p, h = runs[case]["h"]["point"], runs[case]["h"]
        t_ded = p["thrust_deduction"]
        if case.startswith("dtc"):
            t_ded = 1.0 - (R_T - runs[case]["F_D"]) / p["thrust"]
        lines.append(f"| {case} | {p['n']:.3f} | {p['thrust']:.4g} | {p['torque']:.4g} | {p['K_T']:.4f} | "
                     f"{10 * p['K_Q']:.4f} | {p['J']:.4f} | {t_ded:.4f} | {p['wake_fraction']:.4f} | "
                     f"{p['carriage_force']:.2e} | {len(h['time'])} | {settled_text(h['settled'])} |")
    lines += [
        "",
        "Published model self-propulsion values of the DTC at 1.668 m/s (n, T, K_T, K_Q, t, w from el Moctar, "
        "Shigunov & Zorn 2012) were not available on this machine, so no difference to them is stated.\n",
        "| run | cells | steps | simulated s | CPU s | CPU / resistance run | CPU-h per million cells per simulated s "
        "| wall time with no other run of this benchmark going |",
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    base = runs["dtc_towed"]["cpu"]
    for case in names[:3]:
        r = runs[case]
        t = r["h"]["time"][-1]
        per = r["cpu"] / 3600.0 / (r["cells"] / 1e6) / t
        alone = alone_share(case, [c for c in names if c != case])
        lines.append(f"| {case} | {r['cells']} | {len(r['h']['time'])} | {t:.1f} | {r['cpu']:.1f} | "
                     f"{r['cpu'] / base:.3f} | {per:.3g} | {'unknown' if alone is None else f'{100 * alone:.0f}%'} |")
    lines += [
        "",
        "Target: the self-propulsion run costs at most 2x the resistance run. On the shared 2-core machine a run "
        "alone can be faster than one beside another (they share the memory bus), so the like-for-like ratio is "
        "that of runs with the same share alone. The published LFS KCS "
        "self-propulsion took 295 CPU-h on 2.7M cells (109 CPU-h per million cells for the run; its simulated time "
        "is not in the reference data here, so no per-second figure is formed for it). The DTC runs take the "
        "captive campaign's time step on this grid (Courant about 50; 0.15 s diverged at the end of the speed ramp).\n",
    ]
    write_or_print(a.write, NAME, "\n".join(lines))


if __name__ == "__main__":
    main()
