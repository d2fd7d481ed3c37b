#!/usr/bin/env python3
"""Benchmark: hull resistance with the linearized free surface (issue #6,
acceptance 4 and 5).

Runs (unless --report-only) the resistance cases of data/cases/resistance with
`kelvin run`, one at a time under `nice`:
  Wigley (6 m model): double body, then the linearized free surface at
  Fn = 0.25, 0.316, 0.408; DTC (1:59.407) at 1.668 m/s: double body, the
  linearized free surface at maximum Courant number about 100 (dtc_lfs) and
  the same run at about 10 (dtc_lfs_cfl10); the same speed on the finer 53k-cell
  grid of dtc_fine_mesh.yaml, double body and free surface (cell-limited
  gradients). The grids are expected under --grids (kelvin mesh of
  wigley_mesh.yaml, dtc_mesh.yaml and dtc_fine_mesh.yaml).
Then reads each run's resistance.h5 and history.h5 and writes the section
`lfs_resistance` of BENCHMARKS.md:
  - Wigley C_T against the experimental values of the Bai & McCarthy (1979)
    compilation (3.340e-3, 3.620e-3, 4.090e-3), ratio and verdict at 5%;
  - DTC R_T against the measured 31.83 N (el Moctar, Shigunov & Zorn 2012,
    Ship Technology Research 59(3), Table 4), ratio;
  - the Courant study: largest Courant number of each DTC run, its converged
    R_T and the relative difference (target < 0.5%);
  - cost: process CPU time per cell per outer iteration and CPU time until
    R_T stays within 0.1% of its final value and until the steady criterion
    stopped the run, with ratios against the double-body SST peer
    (OpenFOAM simpleFoam, ../shared/peers/openfoam/README.md: 3.1 us per cell
    per SIMPLE iteration on this machine) and against kelvin's own
    double-body run on the same grid.

With --family-runs DIR it also reports the DTC on the three-grid snappyHexMesh
family (free surface and double body, run beforehand by kelvin gci):
  kelvin mesh data/cases/mesh/dtc_snappy.yaml --family 3 -o build/grids/doublebody_dtc
  kelvin gci data/cases/resistance/dtc_fine_lfs.yaml --family 3 --grids build/grids/doublebody_dtc
      --outputs C_T,C_F,C_P --runs DIR/dtc_fine_lfs          (and the same for dtc_fine_double_body)

Usage: tools/bench/lfs_resistance_bench.py --kelvin build/ci/tools/kelvin [--report-only] [--write]
       [--cases wigley_fn0316,dtc_lfs] [--results results] [--family-runs DIR]
"""
import argparse
import datetime
import math
import os
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doublebody_study import ittc57  # noqa: E402
from pimple_vs_openfoam import replace_section  # noqa: E402

NAME = "lfs_resistance"
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
CASES = os.path.join(ROOT, "data", "cases", "resistance")

# Bai & McCarthy (1979) compilation of the Wigley experiments (issue #6).
WIGLEY_EXP = {"wigley_fn0250": (0.250, 3.340e-3), "wigley_fn0316": (0.316, 3.620e-3),
              "wigley_fn0408": (0.408, 4.090e-3)}
# el Moctar, Shigunov & Zorn (2012), Table 4: model 1:59.407 at 1.668 m/s.
DTC_RT_EXP = 31.83
# rho U^2 S / 2 of the DTC family's cases (dtc_fine_*.yaml): N per unit coefficient.
DTC_FAMILY_Q = 0.5 * 998.8 * 1.668 ** 2 * 6.2428
PEER_US_PER_CELL_ITER = 3.1  # OpenFOAM simpleFoam SST double body, peers README
ORDER = ["wigley_double_body", "wigley_fn0250", "wigley_fn0316", "wigley_fn0408", "dtc_double_body", "dtc_lfs",
         "dtc_lfs_cfl10", "dtc_fine_double_body", "dtc_fine_lfs"]
# Grid (kelvin mesh output under build/grids) of each case.
GRIDS = {"wigley": "wigley_lfs", "dtc_fine": "dtc_fine", "dtc": "dtc_lfs"}


def n_cells(poly_mesh):
    with open(os.path.join(poly_mesh, "owner")) as f:
        for line in f:
            if "nCells" in line:
                for tok in line.replace(";", " ").split():
                    if tok.startswith("nCells:"):
                        return int(tok.split(":")[1])
    raise SystemExit(f"no nCells in {poly_mesh}/owner")


def run_case(kelvin, name, results, case=None):
    """`kelvin run` of the case file `case` (default: the shipped case `name`) into <results>/<name>."""
    case = case or os.path.join(CASES, name + ".yaml")
    out = os.path.join(results, name)
    os.makedirs(out, exist_ok=True)
    env = dict(os.environ, OMPI_MCA_ess_singleton_isolated="1")
    with open(os.path.join(out, "run.log"), "w") as log:
        rc = subprocess.call(["nice", kelvin, "run", case, "-o", out, "--no-progress"], stdout=log,
                             stderr=subprocess.STDOUT, env=env)
    if rc != 0:
        print(f"{name}: kelvin run exited with {rc} (see {out}/run.log)", file=sys.stderr)


def failure(name, results):
    """The divergence message of a run without a resistance.h5, if any."""
    for log in (os.path.join(results, name, "run.log"), os.path.join(results, name + ".log")):
        if os.path.isfile(log):
            for line in open(log, errors="replace"):
                if "diverged at step" in line:
                    return line.strip().replace("kelvin: ", "")
    return None


def read(name, results, grids):
    out = os.path.join(results, name)
    r = os.path.join(out, "resistance.h5")
    if not os.path.isfile(r):
        return None
    d = {"name": name}
    with h5py.File(r, "r") as f:
        for k in ("R_T", "R_F", "R_P", "C_T", "C_F", "C_P", "C_W", "R_WL", "C_WL", "Fn", "Re", "speed",
                  "converged", "converged_step"):
            d[k] = float(f[k][0]) if k in f else math.nan
    with h5py.File(os.path.join(out, "history.h5"), "r") as f:
        cpu = f["cpu_time"][:]
        outer = f["outer_iterations"][:]
        co = f["courant"][:]
        fp = f["forces/hull/pressure"][:]
        fv = f["forces/hull/viscous"][:]
    rt = -(fp[:, 0] + fv[:, 0])  # inflow along -x in every case
    final = rt[-1]
    off = np.abs(rt - final) > 1e-3 * abs(final)
    settled = int(np.nonzero(off)[0][-1]) + 1 if off.any() else 0
    settled = min(settled, len(rt) - 1)
    grid = next(g for prefix, g in GRIDS.items() if name.startswith(prefix))
    cells = n_cells(os.path.join(grids, grid, "constant", "polyMesh"))
    d.update(cells=cells, steps=len(cpu), outer=int(outer.sum()), cpu=float(cpu[-1]),
             cpu_settled=float(cpu[settled]), co_max=float(co[len(co) // 2:].max()),
             us_per_cell_iter=1e6 * float(cpu[-1]) / (cells * float(outer.sum())))
    return d


def michell_cw(fn, length=6.0, beam=0.6, draft=0.375, wetted_area=5.3565, g=9.81):
    """Wave-making coefficient of the Wigley hull y = (B/2)(1 - (2x/L)^2)(1 - (z/T)^2)
    by Michell's thin-ship integral (linear theory, Michell 1898; in the form of
    Newman 1977, Marine Hydrodynamics, ch. 6):
        R_W = 4 rho g^2 / (pi U^2) int_1^inf |P + iQ|^2 lambda^2 / sqrt(lambda^2 - 1) d lambda,
        P + iQ = int int f_x(x, z) exp(k0 lambda^2 z + i k0 lambda x) dx dz,  k0 = g / U^2,
    with f the half-breadth. lambda = cosh(t) removes the end-point singularity;
    Gauss-Legendre in x and z. Returned as R_W / (rho U^2 S / 2)."""
    u = fn * math.sqrt(g * length)
    k0 = g / (u * u)
    xg, xw = np.polynomial.legendre.leggauss(400)
    x, wx = 0.5 * length * xg, 0.5 * length * xw
    zg, zw = np.polynomial.legendre.leggauss(80)
    z, wz = -0.5 * draft * (zg + 1), 0.5 * draft * zw
    fx = 0.5 * beam * (-8.0 * x / length ** 2)    # df/dx of the x factor
    fz = 1.0 - (z / draft) ** 2
    # exp(k0 lambda^2 z) < e^-60 over the lower half of the draft beyond this lambda
    t = np.linspace(0.0, math.acosh(math.sqrt(max(120.0 / (k0 * draft), 1.0))) + 1.0, 20000)
    lam = np.cosh(t)
    ix = (fx[None, :] * np.exp(1j * k0 * lam[:, None] * x[None, :]) * wx).sum(axis=1)
    iz = (fz[None, :] * np.exp(k0 * lam[:, None] ** 2 * z[None, :]) * wz).sum(axis=1)
    r_over_rho = 4.0 * g * g / (math.pi * u * u) * np.trapz(np.abs(ix * iz) ** 2 * lam ** 2, t)
    return r_over_rho / (0.5 * u * u * wetted_area)


def implied_wave_table(by, nu=1.14e-6, g=9.81, lengths=(2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 20.0)):
    """What the quoted Wigley C_T leave for waves at other model lengths.

    For a model of length L at the quoted Fn, Re = Fn sqrt(g L) L / nu; the
    viscous part is (C_V / C_F0) C_F0(Re), with the ratio C_V / C_F0 from
    kelvin's own double body (grid and speed of the Fn 0.316 run). The rest,
    C_T,exp - C_V, is the wave part the quoted value leaves; it is shown as a
    fraction of Michell's C_W, beside the fraction kelvin computes. The length
    at which the two agree is found by bisection (None if not below 100 m)."""
    db = by.get("wigley_double_body")
    ref = by.get("wigley_fn0316")
    if not db or not ref or math.isnan(ref["Re"]):
        return []
    form = db["C_T"] / ittc57(ref["Re"])
    lines = ["\n### What the quoted C_T leave for the waves, by model length\n",
             f"Viscous part (C_V / C_F0) C_F0(Re) with C_V / C_F0 = {form:.3f} from kelvin's double body; wave "
             "part left = C_T,exp - C_V, as a fraction of Michell's C_W. The quoted compilation's model lengths "
             "and Reynolds numbers were not found; the runs above assume 6 m.\n",
             "| Fn | kelvin C_W / Michell | " + " | ".join(f"L = {L:g} m" for L in lengths) +
             " | L where the quoted C_T leaves kelvin's C_W | 6 m, no form effect (C_V = C_F0) | "
             "6 m, 1 + k = 1.12 |",
             "| --- | --- | " + " | ".join("---" for _ in lengths) + " | --- | --- | --- |"]

    def left(fn, ct, length, k=form):
        re = fn * math.sqrt(g * length) * length / nu
        return (ct - k * ittc57(re)) / michell_cw(fn)

    for name, (fn, ct) in WIGLEY_EXP.items():
        r = by.get(name)
        if not r or math.isnan(r["C_W"]):
            continue
        target = r["C_W"] / michell_cw(fn)
        lo, hi = 1.0, 100.0
        found = left(fn, ct, hi) >= target
        if found:
            for _ in range(60):
                mid = math.sqrt(lo * hi)
                lo, hi = (mid, hi) if left(fn, ct, mid) < target else (lo, mid)
        cells = " | ".join(f"{left(fn, ct, L):.2f}" for L in lengths)
        lines.append(f"| {fn} | {target:.2f} | {cells} | {f'{hi:.0f} m' if found else 'beyond 100 m'} | "
                     f"{left(fn, ct, 6.0, 1.0):.2f} | {left(fn, ct, 6.0, 1.12):.2f} |")
    return lines


def read_gci(path):
    """A `kelvin gci` report of C_T, C_F and C_P: per grid (finest first) the cells, steps, CPU time, outer
    iterations and whether the run settled; per output its values and the Richardson analysis."""
    with h5py.File(path, "r") as f:
        d = {"cells": f["grids/cells"][:], "steps": f["grids/steps"][:], "cpu": f["grids/cpu_time"][:],
             "iters": f["grids/outer_iterations"][:], "settled": f["grids/steady_converged"][:]}
        for out in ("C_T", "C_F", "C_P"):
            g = f["outputs/" + out]
            d[out] = {k: g[k][:] if k == "values" else float(g[k][0])
                      for k in ("values", "R", "p", "extrapolated", "gci_fine", "gci_coarse", "asymptotic_ratio")}
            conv = g.attrs["convergence"]
            d[out]["convergence"] = conv.decode() if isinstance(conv, bytes) else str(conv)
    return d


def family_section(runs):
    """DTC at 1.668 m/s on the three snappyHexMesh grids of data/cases/mesh/dtc_snappy.yaml --family 3: the
    free-surface case dtc_fine_lfs.yaml and its double body dtc_fine_double_body.yaml run by `kelvin gci` (reports
    <runs>/<case>/gci.h5). Returns the lines of the subsection, or [] when the reports are missing."""
    reports = {name: os.path.join(runs, name, "gci.h5") for name in ("dtc_fine_lfs", "dtc_fine_double_body")}
    if not all(os.path.isfile(f) for f in reports.values()):
        return []
    data = {name: read_gci(path) for name, path in reports.items()}
    q = DTC_FAMILY_Q
    lfs, db = data["dtc_fine_lfs"], data["dtc_fine_double_body"]
    lines = ["\n### DTC on a three-grid family: free surface and double body (`kelvin gci`)\n",
             "`kelvin mesh data/cases/mesh/dtc_snappy.yaml --family 3` (snappyHexMesh, ratio sqrt 2 in the base "
             "cells; grid 3, 52,920 cells, is nearly the grid of `dtc_fine_mesh.yaml`, 52,969), then `kelvin gci` with the cases "
             "`dtc_fine_lfs.yaml` and `dtc_fine_double_body.yaml` (cell-limited gradients). R = C q with "
             f"q = rho U^2 S / 2 = {q:.1f} N; measured R_T 31.83 N.\n",
             "| grid | cells | R_T LFS (N) | R_T / 31.83 | R_F LFS (N) | R_P LFS (N) | R_T double body (N) | "
             "R_P double body (N) | R_W = R_P - R_P(db) (N) | steps LFS / db | converged LFS / db | CPU s LFS / db |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for g in range(len(lfs["cells"])):
        ct, cf, cp = (lfs[o]["values"][g] for o in ("C_T", "C_F", "C_P"))
        dct, dcp = db["C_T"]["values"][g], db["C_P"]["values"][g]
        lines.append(f"| {g + 1} | {int(lfs['cells'][g])} | {ct * q:.3f} | {ct * q / DTC_RT_EXP:.3f} | {cf * q:.3f} | "
                     f"{cp * q:.3f} | {dct * q:.3f} | {dcp * q:.3f} | {(cp - dcp) * q:+.3f} | "
                     f"{int(lfs['steps'][g])} / {int(db['steps'][g])} | "
                     f"{'yes' if lfs['settled'][g] else '**no**'} / {'yes' if db['settled'][g] else '**no**'} | "
                     f"{lfs['cpu'][g]:.0f} / {db['cpu'][g]:.0f} |")
    lines += ["", "| case | output | R | convergence | p | extrapolated (N) | R_T extrapolated / 31.83 | GCI_fine | "
                  "GCI_coarse | GCI32 / (r^p GCI21) |",
              "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for name, d in data.items():
        for out in ("C_T", "C_F", "C_P"):
            o = d[out]
            if o["convergence"] == "divergent":  # no extrapolation or GCI for divergent outputs
                lines.append(f"| {name} | {out} | {o['R']:.3f} | divergent | | | | | | |")
                continue
            ratio = f"{o['extrapolated'] * q / DTC_RT_EXP:.3f}" if out == "C_T" else ""
            lines.append(f"| {name} | {out} | {o['R']:.3f} | {o['convergence']} | {o['p']:.2f} | "
                         f"{o['extrapolated'] * q:.3f} | {ratio} | "
                         f"{100 * o['gci_fine']:.2f}% | {100 * o['gci_coarse']:.2f}% | {o['asymptotic_ratio']:.3f} |")
    return lines


def fmt(x, spec):
    return "n/a" if x is None or (isinstance(x, float) and math.isnan(x)) else format(x, spec)


def section(rows, failed=None, family_runs=None):
    by = {r["name"]: r for r in rows}
    failed = failed or {}
    lines = ["## LFS hull resistance (issue #6, acceptance 4 and 5)\n",
             f"Written by `tools/bench/lfs_resistance_bench.py` on {datetime.date.today()}; "
             "k-omega SST with wall functions, linearized free surface on `freeSurface`, relaxed PIMPLE "
             "(U 0.7, p 0.3, final corrector U 0.7; k/omega 0.7; outer correctors as in each case file) from rest, the "
             "surface held as a rigid lid for one flow-through and then released, marching in pseudo-time until "
             "R_T, R_F, R_P and eta change by < 0.1% over one flow-through (at least 20 steps). Process CPU time, serial, under `nice` on the "
             "shared 2-core machine.\n"]
    lines.append("### Wigley hull (6 m model, fresh water 15 C), C_T against experiment\n")
    lines.append("| Fn | Re | C_T kelvin | C_T exp. | ratio | within 5% | C_F | C_P | C_W = C_P - C_P(db) | "
                 "C_W Michell (thin ship) | C_WL (separate) | converged |")
    lines.append("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for name, (fn, ct) in WIGLEY_EXP.items():
        r = by.get(name)
        if not r:
            lines.append(f"| {fn} | | {failed.get(name, 'not run')} | {ct:.3e} | | | | | | "
                         f"{michell_cw(fn):.3e} | | |")
            continue
        ratio = r["C_T"] / ct
        lines.append(f"| {fn} | {fmt(r['Re'], '.3g')} | {r['C_T']:.4e} | {ct:.3e} | {ratio:.3f} | "
                     f"{'yes' if abs(ratio - 1) <= 0.05 else '**no**'} | {r['C_F']:.4e} | {r['C_P']:.4e} | "
                     f"{fmt(r['C_W'], '.3e')} | {michell_cw(fn):.3e} | {fmt(r['C_WL'], '.2e')} | "
                     f"{'yes' if r['converged'] == 1 else '**no**'} |")
    db = by.get("wigley_double_body")
    if db:
        lines.append(f"\nDouble body (Fn 0.316 speed): C_T {db['C_T']:.4e}, C_F {db['C_F']:.4e}, "
                     f"C_P {db['C_P']:.4e}.\n")
    lines.extend(implied_wave_table(by))
    lines.append("\n### DTC at 1.668 m/s (model 1:59.407, fixed at the design waterline)\n")
    lines.append("| run | max Courant | R_T (N) | R_T / measured 31.83 N | R_F (N) | R_P (N) | C_T | C_W | "
                 "converged | steps |")
    lines.append("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for name in ("dtc_double_body", "dtc_lfs", "dtc_lfs_cfl10", "dtc_fine_double_body", "dtc_fine_lfs"):
        r = by.get(name)
        dtc_db = by.get("dtc_fine_double_body" if name.startswith("dtc_fine") else "dtc_double_body")
        if r and "double_body" not in name and math.isnan(r["C_W"]) and dtc_db:
            r["C_W"] = r["C_P"] - dtc_db["C_P"]  # C_W = C_P - C_P(double body), same grid and speed
        if not r:
            lines.append(f"| {name} | {failed.get(name, 'not run')} | | | | | | | | |")
            continue
        lines.append(f"| {name} | {r['co_max']:.0f} | {r['R_T']:.3f} | {r['R_T'] / DTC_RT_EXP:.3f} | "
                     f"{r['R_F']:.3f} | {r['R_P']:.3f} | {r['C_T']:.4e} | {fmt(r['C_W'], '.3e')} | "
                     f"{'yes' if r['converged'] == 1 else '**no**'} | {r['steps']} |")
    a, b = by.get("dtc_lfs"), by.get("dtc_lfs_cfl10")
    if a and b:
        diff = (a["R_T"] - b["R_T"]) / b["R_T"]
        lines.append(f"\nCourant study: R_T at Courant {a['co_max']:.0f} differs from Courant {b['co_max']:.0f} by "
                     f"{100 * diff:+.3f}% (target < 0.5%: {'met' if abs(diff) < 5e-3 else '**missed**'}).\n")
    lines.extend(family_section(family_runs) if family_runs else [])
    lines.append("\n### Cost\n")
    lines.append("| run | cells | outer iterations | CPU s | us per cell per iteration | ratio to simpleFoam "
                 "peer (3.1 us) | CPU s until R_T within 0.1% of final | CPU s to the stop |")
    lines.append("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for name in ORDER:
        r = by.get(name)
        if not r:
            continue
        lines.append(f"| {name} | {r['cells']} | {r['outer']} | {r['cpu']:.0f} | {r['us_per_cell_iter']:.2f} | "
                     f"{r['us_per_cell_iter'] / PEER_US_PER_CELL_ITER:.2f} | {r['cpu_settled']:.0f} | "
                     f"{r['cpu']:.0f} |")
    for lfs, dbn in (("dtc_lfs", "dtc_double_body"), ("wigley_fn0316", "wigley_double_body")):
        x, y = by.get(lfs), by.get(dbn)
        if x and y:
            lines.append(f"\n{lfs} / kelvin double body on the same grid: CPU to the stop "
                         f"{x['cpu'] / y['cpu']:.2f}, per cell per iteration "
                         f"{x['us_per_cell_iter'] / y['us_per_cell_iter']:.2f}.")
    lines.append("\nThe simpleFoam figure is the peer README's measurement on this machine (127k-cell DTC double "
                 "body), not re-run by this tool; the peer benchmark proper is acceptance 6.\n")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kelvin", default=os.path.join(ROOT, "build", "ci", "tools", "kelvin"))
    ap.add_argument("--results", default=os.path.join(ROOT, "results"))
    ap.add_argument("--grids", default=os.path.join(ROOT, "build", "grids"))
    ap.add_argument("--cases", default=",".join(ORDER), help="comma-separated subset to run")
    ap.add_argument("--report-only", action="store_true", help="only read existing results")
    ap.add_argument("--write", action="store_true", help="write the section into BENCHMARKS.md")
    ap.add_argument("--output", default=os.path.join(ROOT, "BENCHMARKS.md"))
    ap.add_argument("--note", default=None, help="file with measured findings to append to the section")
    ap.add_argument("--family-runs", default=None,
                    help="directory of the kelvin gci runs of dtc_fine_lfs and dtc_fine_double_body on the "
                         "dtc_snappy.yaml family (<dir>/<case>/gci.h5)")
    args = ap.parse_args()
    names = [n for n in args.cases.split(",") if n]
    if not args.report_only:
        for n in names:
            run_case(args.kelvin, n, args.results)
    rows = [r for r in (read(n, args.results, args.grids) for n in ORDER) if r]
    failed = {n: failure(n, args.results) for n in ORDER}
    text = section(rows, {n: m for n, m in failed.items() if m and n not in {r["name"] for r in rows}},
                   args.family_runs)
    if args.note:
        text += "\n" + open(args.note).read().strip() + "\n"
    print(text)
    if args.write:
        replace_section(args.output, NAME, text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
