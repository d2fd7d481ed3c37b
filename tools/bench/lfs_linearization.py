#!/usr/bin/env python3
"""Benchmark: the two linearizations of the free-surface kinematic condition side by side (issue #22,
acceptance 2 and 3; docs/formulation.md section 3.1).

On the same grid and at the same speed, `kelvin run` of
  - the double body (the free surface a rigid lid: R_P(db));
  - the linearized free surface carried by the uniform stream (-u_b, Neumann-Kelvin: the case as shipped);
  - the same with `linearization: local_flow` (carried by the flow under the surface, double-body type);
for the DTC at 1.668 m/s (data/cases/resistance/dtc_lfs.yaml, dtc_double_body.yaml; measured R_T 31.83 N and
wave part R_T - R_T(double body, measured) 2.91 N, el Moctar, Shigunov & Zorn 2012) and the 6 m Wigley at
Fn 0.316 (wigley_fn0316.yaml, wigley_double_body.yaml; C_W against Michell's thin-ship value). The wave part is
R_W = R_P - R_P(db) on the same grid. Writes the section `lfs_linearization` of BENCHMARKS.md.

The grids are expected under --grids (kelvin mesh data/cases/resistance/dtc_mesh.yaml and wigley_mesh.yaml).
The section also tabulates the DTC three-grid family, from the `kelvin gci` reports that tools/bench/dtc_family.sh
leaves under --family-runs (each case with a report; none without the double body's).

Usage: tools/bench/lfs_linearization.py [--kelvin build/ci/tools/kelvin] [--hulls dtc,wigley] [--runs LABELS]
       [--report-only] [--write] [--results DIR]
"""
import argparse
import datetime
import os
import sys

import h5py

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from case_variants import ROOT, variant_case  # noqa: E402
from lfs_resistance_bench import DTC_FAMILY_Q, DTC_RT_EXP, failure, michell_cw, read, read_gci, run_case  # noqa: E402
from pimple_vs_openfoam import write_or_print  # noqa: E402

NAME = "lfs_linearization"
CASES = os.path.join(ROOT, "data", "cases", "resistance")
LOCAL = {"boundary.freeSurface.p.linearization": "local_flow"}
# Per hull: the runs (label, case, overrides), the double body first.
RUNS = {
    "dtc": [("dtc_double_body", "dtc_double_body", None), ("dtc_lfs", "dtc_lfs", None),
            ("dtc_lfs_local", "dtc_lfs", LOCAL)],
    "wigley": [("wigley_double_body", "wigley_double_body", None), ("wigley_fn0316", "wigley_fn0316", None),
               ("wigley_fn0316_local", "wigley_fn0316", LOCAL)],
}
DTC_RW_EXP = 2.91  # measured R_T less the measured double-body resistance (issue #22)


def run(kelvin, label, case, overrides, results):
    path = variant_case(os.path.join(CASES, case + ".yaml"), os.path.join(results, label, "case.yaml"), overrides)
    run_case(kelvin, label, results, path)


def section(rows, results, family=None):
    by = {r["name"]: r for r in rows}
    lines = ["## lfs_linearization: the kinematic condition's two linearizations side by side (issue #22, "
             "acceptance 2 and 3)\n",
             f"Written by `tools/bench/lfs_linearization.py` on {datetime.date.today()}: on one grid per hull, the "
             "double body and the free surface with each linearization of the kinematic condition "
             "(docs/formulation.md section 3.1): `uniform_stream` (the pattern carried by -u_b) and `local_flow` "
             "(carried by the flow under the surface). R_W = R_P - R_P(double body). Cases as shipped otherwise "
             "(k-omega SST with wall functions, rigid-lid start, pseudo-transient to the steady criterion). "
             "Serial, under `nice`, beside other work on the 2-core machine.\n",
             "| run | linearization | R_T (N) | R_F (N) | R_P (N) | R_W (N) | C_T | C_W | C_W / reference | "
             "converged | steps | CPU s |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for hull, runs in RUNS.items():
        db = by.get(runs[0][0])
        for label, _, overrides in runs:
            r = by.get(label)
            if not r:
                lines.append(f"| {label} | | {failure(label, results) or 'not run'} | | | | | | | | | |")
                continue
            lin = "double body" if label == runs[0][0] else ("local_flow" if overrides else "uniform_stream")
            rw = cw = ref = ""
            if db and r is not db:
                rw = f"{r['R_P'] - db['R_P']:+.3f}"
                c_w = r["C_P"] - db["C_P"]
                cw = f"{c_w:.3e}"
                ref = (f"{(r['R_P'] - db['R_P']) / DTC_RW_EXP:.2f} of the measured {DTC_RW_EXP} N" if hull == "dtc"
                       else f"{c_w / michell_cw(0.316):.2f} of Michell")
            lines.append(f"| {label} | {lin} | {r['R_T']:.3f} | {r['R_F']:.3f} | {r['R_P']:.3f} | {rw} | "
                         f"{r['C_T']:.4e} | {cw} | {ref} | {'yes' if r['converged'] == 1 else '**no**'} | "
                         f"{r['steps']} | {r['cpu']:.0f} |")
    dtc = by.get("dtc_lfs_local")
    if dtc:
        lines.append(f"\nDTC R_T with the local flow: {dtc['R_T']:.3f} N, {dtc['R_T'] / DTC_RT_EXP:.3f} of the measured "
                     f"{DTC_RT_EXP} N (el Moctar, Shigunov & Zorn 2012).")
    lines.extend(family_lines(family) if family else [])
    return "\n".join(lines) + "\n"


# The DTC three-grid family (tools/bench/dtc_family.sh: `kelvin gci` of each case on
# data/cases/mesh/dtc_snappy.yaml --family 3), the double body first.
FAMILY = [("dtc_fine_double_body", "double body"), ("dtc_fine_lfs", "uniform_stream"),
          ("dtc_fine_lfs_local", "local_flow")]


def deepest_trough(run_dir):
    """The lowest surface elevation of a run (m) and where, from its resistance.h5, or None."""
    path = os.path.join(run_dir, "resistance.h5")
    if not os.path.isfile(path):
        return None
    with h5py.File(path, "r") as f:
        if "surface/eta" not in f:
            return None
        eta, x, y = f["surface/eta"][:], f["surface/x"][:], f["surface/y"][:]
    k = int(eta.argmin())
    return eta[k], x[k], y[k]


def family_lines(runs):
    """The family table of every case with a gci.h5 under `runs`; [] without the double body's."""
    data = {name: read_gci(os.path.join(runs, name, "gci.h5")) for name, _ in FAMILY
            if os.path.isfile(os.path.join(runs, name, "gci.h5"))}
    if FAMILY[0][0] not in data:
        return []
    db = data[FAMILY[0][0]]
    q = DTC_FAMILY_Q
    lines = ["\n### The DTC three-grid family (`kelvin gci`)\n",
             "`tools/bench/dtc_family.sh`: `kelvin gci` of `dtc_fine_double_body.yaml`, `dtc_fine_lfs.yaml` and the "
             "same with `linearization: local_flow` on the grids of `kelvin mesh data/cases/mesh/dtc_snappy.yaml "
             f"--family 3`. R = C q with q = {q:.1f} N; R_W = R_P - R_P(double body) on the same grid; measured "
             f"R_T {DTC_RT_EXP} N and R_W {DTC_RW_EXP} N. The deepest trough is the lowest eta of the run's surface "
             "(U^2/2g = 0.142 m).\n",
             "| grid | cells | case | R_T (N) | R_T / 31.83 | R_F (N) | R_P (N) | R_W (N) | deepest trough (m, at x, y) | "
             "steps | settled | CPU s |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for g in range(len(db["cells"])):
        for name, label in FAMILY:
            d = data.get(name)
            if d is None:
                continue
            ct, cf, cp = (d[o]["values"][g] for o in ("C_T", "C_F", "C_P"))
            rw = "" if d is db else f"{(cp - db['C_P']['values'][g]) * q:+.3f}"
            trough = deepest_trough(os.path.join(runs, name, f"grid{g + 1}"))
            where = "" if trough is None else f"{trough[0]:+.3f} at ({trough[1]:.2f}, {trough[2]:.2f})"
            lines.append(f"| {g + 1} | {int(d['cells'][g])} | {label} | {ct * q:.3f} | {ct * q / DTC_RT_EXP:.3f} | "
                         f"{cf * q:.3f} | {cp * q:.3f} | {rw} | {where} | {int(d['steps'][g])} | "
                         f"{'yes' if d['settled'][g] else '**no**'} | {d['cpu'][g]:.0f} |")
    lines += ["", "| case | output | R | convergence | p | extrapolated (N) | extrapolated / 31.83 | GCI_fine |",
              "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for name, label in FAMILY:
        d = data.get(name)
        if d is None:
            lines.append(f"| {label} | | not run on this family | | | | | |")
            continue
        for out in ("C_T", "C_P"):
            o = d[out]
            if o["convergence"] == "divergent":
                lines.append(f"| {label} | {out} | {o['R']:.3f} | divergent | | | | |")
                continue
            ratio = f"{o['extrapolated'] * q / DTC_RT_EXP:.3f}" if out == "C_T" else ""
            lines.append(f"| {label} | {out} | {o['R']:.3f} | {o['convergence']} | {o['p']:.2f} | "
                         f"{o['extrapolated'] * q:.3f} | {ratio} | {100 * o['gci_fine']:.2f}% |")
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kelvin", default=os.path.join(ROOT, "build", "ci", "tools", "kelvin"))
    ap.add_argument("--results", default=os.path.join(ROOT, "build", "bench", NAME))
    ap.add_argument("--grids", default=os.path.join(ROOT, "build", "grids"))
    ap.add_argument("--hulls", default="dtc,wigley")
    ap.add_argument("--family-runs", default=os.path.join(ROOT, "build", "bench", "dtc_family"),
                    help="the runs of tools/bench/dtc_family.sh, for the three-grid table")
    ap.add_argument("--report-only", action="store_true")
    ap.add_argument("--runs", default="", help="comma-separated labels to run again (default: every run of --hulls)")
    ap.add_argument("--write", nargs="?", const=os.path.join(ROOT, "BENCHMARKS.md"), default=None,
                    help="write the section into this file (default BENCHMARKS.md)")
    args = ap.parse_args()
    hulls = [h for h in args.hulls.split(",") if h]
    for h in hulls:
        if h not in RUNS:
            raise SystemExit(f"--hulls: {h!r}; expected some of {', '.join(RUNS)}")
    labels = {label for runs in RUNS.values() for label, _, _ in runs}
    only = {r for r in args.runs.split(",") if r}
    if only - labels:
        raise SystemExit(f"--runs: {', '.join(sorted(only - labels))}; expected some of {', '.join(sorted(labels))}")
    if not args.report_only:
        for h in hulls:
            for label, case, overrides in RUNS[h]:
                if not only or label in only:
                    run(args.kelvin, label, case, overrides, args.results)
    rows = [r for runs in RUNS.values() for label, _, _ in runs
            if (r := read(label, args.results, args.grids)) is not None]
    write_or_print(args.write, NAME, section(rows, args.results, args.family_runs))


if __name__ == "__main__":
    main()
