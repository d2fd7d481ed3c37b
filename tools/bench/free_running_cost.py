#!/usr/bin/python3
"""Benchmark: free-running CFD, section `free_running_cost` of BENCHMARKS.md.

Runs, one after the other on one core each (so that their CPU times compare),
`kelvin run` on
  - data/cases/free_running/dtc_towed.yaml            (the resistance run),
  - data/cases/free_running/dtc_self_propulsion.yaml  (model point, F_D = 0),
  - data/cases/free_running/dtc_self_propulsion_ship.yaml (ship point, F_D = 13.947 N),
  - data/cases/free_running/wigley_self_propulsion.yaml,
all on the grids their files name (build the DTC grid first with
`kelvin mesh data/cases/resistance/dtc_fine_mesh.yaml`, the Wigley grid with
`kelvin mesh data/cases/captive_cfd/wigley_quick_mesh.yaml`), and tabulates
  - the self-propulsion points (n, T, Q, K_T, 10 K_Q, J, t, w_T) from each
    history.h5 `self_propulsion/` group, the towed R_T and the grid's friction
    against ITTC-57;
  - the cost: the CPU of the self-propulsion run against the resistance run of
    the same hull and grid (target at most 2), and CPU-hours per million cells
    per simulated second, beside the published LFS figure (295 CPU-h on 2.7M
    cells for the KCS self-propulsion; shared/reference/kcs_conditions.yaml).

Usage: tools/bench/free_running_cost.py --kelvin build/ci/tools/kelvin [--write BENCHMARKS.md]
"""
import argparse
import math
import os
import resource
import subprocess
import sys

import h5py

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doublebody_study import ittc57  # noqa: E402
from pimple_vs_openfoam import write_or_print  # noqa: E402

NAME = "free_running_cost"
ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
CASES = os.path.join(ROOT, "data", "cases", "free_running")
RESULTS = os.path.join(ROOT, "results", "free_running")
RHO, U, S, L, NU = 998.8, 1.668, 6.2428, 5.976, 1.09e-6  # the DTC model (data/ships/dtc.yaml)


def run(kelvin, case):
    """Runs one case; returns (CPU seconds of the child, its results directory)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    env = dict(os.environ, OMPI_MCA_ess_singleton_isolated="1")
    out = subprocess.run([kelvin, "run", os.path.join(CASES, case + ".yaml"), "--no-progress"], env=env,
                         capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if out.returncode != 0:
        sys.exit(f"{case}: kelvin run failed:\n{out.stdout}\n{out.stderr}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, os.path.join(RESULTS, case), out.stdout + out.stderr


def history(directory):
    with h5py.File(os.path.join(directory, "history.h5"), "r") as f:
        h = {"time": f["time"][:], "hull": f["body/hull_load"][:], "viscous": f["forces/hull/viscous"][:]}
        if "self_propulsion" in f:
            h["point"] = {k: float(f["self_propulsion"][k][0]) for k in f["self_propulsion"]}
    return h


def cells(stdout):
    for line in stdout.splitlines():
        if line.startswith("cells "):
            return int(line.split()[1])
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kelvin", required=True)
    ap.add_argument("--write", help="replace the section in this file (e.g. BENCHMARKS.md)")
    a = ap.parse_args()

    runs = {}
    for case in ["dtc_towed", "dtc_self_propulsion", "dtc_self_propulsion_ship", "wigley_self_propulsion"]:
        cpu, directory, stdout = run(a.kelvin, case)
        runs[case] = {"cpu": cpu, "h": history(directory), "cells": cells(stdout)}
        print(f"{case}: {cpu:.1f} CPU s, {len(runs[case]['h']['time'])} steps", file=sys.stderr)

    towed = runs["dtc_towed"]["h"]
    R_T = -towed["hull"][-1, 0]
    R_F = -towed["viscous"][-1, 0]
    R_F0 = ittc57(U * L / NU) * 0.5 * RHO * S * U * U
    lines = [
        "## Free running: self-propulsion and its cost\n",
        "Produced by `tools/bench/free_running_cost.py` (release build; the runs one after the other, one core each). "
        "The hulls are towed at constant speed in the earth frame (surge held, the CFD form of a self-propulsion "
        "test) with the body-force propeller of their ship files, the rate controlled until the carriage force "
        "vanishes (`data/cases/free_running/`). The DTC propeller and open-water table are those of the "
        "OpenFOAM-dev DTCHullProp tutorial; the Wigley's propeller is assumed (data/ships/wigley.yaml).\n",
        f"DTC grid (dtc_fine_mesh.yaml, {runs['dtc_towed']['cells']} cells): towed R_T = {R_T:.3f} N "
        f"(measured 31.83 N, el Moctar et al. 2012), R_F = {R_F:.2f} N = {R_F / R_F0:.3f} of ITTC-57 "
        f"({R_F0:.2f} N): this grid's friction is short, so the propeller works against a low resistance; its disk "
        "is 3.9 cells across (kelvin warns).\n",
        "| run | n (1/s) | T (N) | Q (N m) | K_T | 10 K_Q | J (disk) | t | w_T | carriage force left (N) | steps |",
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    for case in ["dtc_self_propulsion", "dtc_self_propulsion_ship", "wigley_self_propulsion"]:
        p = runs[case]["h"]["point"]
        lines.append(f"| {case} | {p['n']:.3f} | {p['thrust']:.4g} | {p['torque']:.4g} | {p['K_T']:.4f} | "
                     f"{10 * p['K_Q']:.4f} | {p['J']:.4f} | {p['thrust_deduction']:.4f} | {p['wake_fraction']:.4f} | "
                     f"{p['carriage_force']:.2e} | {len(runs[case]['h']['time'])} |")
    lines += [
        "",
        "Published model self-propulsion values of the DTC at 1.668 m/s (n, T, K_T, K_Q, t, w from el Moctar, "
        "Shigunov & Zorn 2012) were not available on this machine, so no difference to them is stated.\n",
        "| run | cells | steps | simulated s | CPU s | CPU / resistance run | CPU-h per million cells per simulated s |",
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    base = runs["dtc_towed"]["cpu"]
    for case in ["dtc_towed", "dtc_self_propulsion", "dtc_self_propulsion_ship"]:
        r = runs[case]
        t = r["h"]["time"][-1]
        per = r["cpu"] / 3600.0 / (r["cells"] / 1e6) / t
        lines.append(f"| {case} | {r['cells']} | {len(r['h']['time'])} | {t:.1f} | {r['cpu']:.1f} | "
                     f"{r['cpu'] / base:.3f} | {per:.3g} |")
    lines += [
        "",
        "Target: the self-propulsion run costs at most 2x the resistance run. The published LFS KCS "
        "self-propulsion took 295 CPU-h on 2.7M cells (109 CPU-h per million cells for the run; its simulated time "
        "is not in the reference data here, so no per-second figure is formed for it). These DTC runs march in "
        "pseudo-time at Courant about 180 to the steady point, where the published run was time-accurate.\n",
    ]
    write_or_print(a.write, NAME, "\n".join(lines))


if __name__ == "__main__":
    main()
