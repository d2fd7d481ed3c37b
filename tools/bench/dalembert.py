#!/usr/bin/env python3
"""Benchmark: d'Alembert's test of the discretization (issue 22, acceptance 1).

The submerged 5:1 prolate spheroid of data/cases/resistance/spheroid_dalembert_mesh.yaml in a steady stream, slip
walls everywhere (the body included) and no turbulence model: the flow is irrotational up to the scheme's own
losses, so the pressure resistance must fall to zero as the grid is refined and the stagnation points must reach
C_p = 1. The script
  - meshes the three-grid snappy family (`kelvin mesh ... --family 3`) unless it is there,
  - runs data/cases/resistance/spheroid_dalembert.yaml on each grid through `kelvin gci` (once per --variant, each
    a mapping of the case's keys to set, e.g. the hull's pressure condition or the schemes),
  - reads R_P, C_P and the hull's pressure per face (resistance.h5) and reports, per grid, R_P, its share of the
    viscous run's R_T, the largest C_p at the bow and at the stern (cell values on the wall faces, which is what
    the forces integrate), the fore- and after-body parts of R_P, and the observed order of R_P against the exact
    zero between neighbouring grids (h: the hull cell size of the grid's quality.txt).
The viscous reference R_T is that of data/cases/resistance/spheroid_double_body.yaml (the same body, no-slip,
k-omega SST with wall functions, on its own grid; --viscous-rt, or --viscous to run it).

Usage:
  tools/bench/dalembert.py --kelvin build/ci/tools/kelvin [--variant 'NAME={key.key: value, ...}' ...] [--viscous]
                           [--work DIR] [--write BENCHMARKS.md]
"""
import argparse
import datetime
import math
import os
import re
import subprocess
import sys

import h5py
import numpy as np
import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from case_variants import variant_case  # noqa: E402
from pimple_vs_openfoam import write_or_print  # noqa: E402

NAME = "dalembert"
ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
CASES = os.path.join(ROOT, "data", "cases", "resistance")
MESH_CASE = os.path.join(CASES, "spheroid_dalembert_mesh.yaml")
CASE = os.path.join(CASES, "spheroid_dalembert.yaml")
GRIDS = os.path.join(ROOT, "build", "grids", "spheroid_dalembert")
SPEED, RHO, LENGTH = 1.566, 998.2, 1.0  # the case's inflow speed (m/s), density, body length (m, bow at x = L)


def run(cmd, log):
    print("+", " ".join(cmd), flush=True)
    env = dict(os.environ, OMPI_MCA_ess_singleton_isolated="1")
    with open(log, "w") as f:
        if subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT, env=env).returncode != 0:
            sys.exit(f"failed: {' '.join(cmd)} (log: {log})")


def hull_cell(grid_dir):
    with open(os.path.join(grid_dir, "quality.txt")) as f:
        m = re.search(r"hull cell ([0-9.eE+-]+) m", f.read())
    if not m:
        sys.exit(f"{grid_dir}/quality.txt: no 'hull cell' line (a snappy grid was expected)")
    return float(m.group(1))


def wall_cp(run_dir):
    """Largest C_p at the bow and at the stern, and the fore-/after-body parts of R_P (N)."""
    with h5py.File(os.path.join(run_dir, "resistance.h5"), "r") as f:
        centre, area = f["hull_faces/centre"][:], f["hull_faces/area"][:]
        force, d = f["hull_faces/pressure_force"][:], f["hull_faces/direction"][:]
        r_p, c_p = float(f["R_P"][()]), float(f["C_P"][()])
    mag = np.linalg.norm(area, axis=1)
    cp = (force * area).sum(axis=1) / mag ** 2 / RHO / (0.5 * SPEED ** 2)
    fore = centre[:, 0] > 0.5 * LENGTH
    drag = force @ d
    return dict(R_P=r_p, C_P=c_p, cp_bow=float(cp[fore].max()), cp_stern=float(cp[~fore].max()),
                fore=float(drag[fore].sum()), aft=float(drag[~fore].sum()))


def variant(work, name, overrides):
    """The case with `overrides` (dotted keys) set, in `work`."""
    return variant_case(CASE, os.path.join(work, f"case_{name}.yaml"), overrides)


def viscous_rt(kelvin, work):
    grid = os.path.join(ROOT, "build", "grids", "spheroid_fn050")
    if not os.path.exists(os.path.join(grid, "constant", "polyMesh")):
        run([kelvin, "mesh", os.path.join(CASES, "spheroid_mesh.yaml")], os.path.join(work, "mesh_viscous.log"))
    out = os.path.abspath(os.path.join(work, "viscous"))
    with open(os.path.join(CASES, "spheroid_double_body.yaml")) as f:
        text = f.read().replace("../../../", ROOT + "/")
    text = re.sub(r"directory: [^,}]*", f"directory: {out}", text)
    path = os.path.join(work, "case_viscous.yaml")
    with open(path, "w") as f:
        f.write(text)
    run([kelvin, "run", path], os.path.join(work, "viscous.log"))
    with h5py.File(os.path.join(out, "resistance.h5"), "r") as f:
        return float(f["R_T"][()])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kelvin", required=True)
    ap.add_argument("--grids", default=GRIDS, help="family directory (meshed from the mesh case when missing)")
    ap.add_argument("--variant", action="append", default=[],
                    help="NAME=OVERRIDES: a run of the family with the case's keys set, OVERRIDES a YAML mapping of "
                         "dotted keys (e.g. '{schemes.convection: lust}'; repeatable; NAME=: the case as it is; "
                         "default: the case as it is)")
    ap.add_argument("--viscous", action="store_true", help="run the viscous reference (spheroid_double_body)")
    ap.add_argument("--viscous-rt", type=float, default=None, help="the viscous reference R_T (N), if known")
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "bench", "dalembert"))
    ap.add_argument("--write", help="BENCHMARKS.md to update (default: print the section)")
    ap.add_argument("--reuse", action="store_true",
                    help="take a variant's runs from an earlier invocation in --work when its gci.yaml is there")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    if not os.path.exists(os.path.join(args.grids, "family.txt")):
        run([args.kelvin, "mesh", MESH_CASE, "--family", "3", "-o", args.grids], os.path.join(args.work, "mesh.log"))
    rt = viscous_rt(args.kelvin, args.work) if args.viscous else args.viscous_rt
    variants = [[n, o or None] for n, o in (v.split("=", 1) for v in args.variant)] or [["case", None]]
    tables = []
    for name, overrides in variants:
        runs = os.path.join(args.work, name)
        if not (args.reuse and os.path.exists(os.path.join(runs, "gci.yaml"))):
            run([args.kelvin, "gci", variant(args.work, name, overrides), "--grids", args.grids, "--outputs", "C_P",
                 "--runs", runs, "--rerun", "--no-progress",
                 # the base cells are whole numbers per length (28, 20, 14), so the ratios differ by 1%
                 "--ratio-tolerance", "0.1"], os.path.join(args.work, f"gci_{name}.log"))
        with open(os.path.join(runs, "gci.yaml")) as f:
            report = yaml.safe_load(f)
        rows = []
        for g in sorted(report["grids"], key=lambda g: -g["level"]):
            r = wall_cp(g["directory"])
            r.update(level=g["level"], cells=g["cells"], steps=g["steps"], settled=g["steady_converged"],
                     cpu=g["cpu_seconds"], hull=hull_cell(os.path.join(args.grids, f"grid{g['level']}")),
                     h=g["h"])
            rows.append(r)
        tables.append((name, overrides, rows))
    write_or_print(args.write, NAME, render(tables, rt, args.grids))


def order(coarse, fine, h):
    """The observed order of R_P against zero between two grids, h their cell size (the row's key `h`)."""
    if coarse is None:
        return ""
    if coarse["R_P"] <= 0 or fine["R_P"] <= 0:
        return "n/a"
    return f"{math.log(coarse['R_P'] / fine['R_P']) / math.log(coarse[h] / fine[h]):.2f}"


def render(tables, rt, grids):
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    rel = os.path.relpath(grids, ROOT)
    out = [f"""## dalembert: pressure resistance of an inviscid closed body (issue 22, acceptance 1)

Run by `tools/bench/dalembert.py` on {date}. The submerged 5:1 prolate spheroid (L = 1 m, axis 0.25 m under a slip
lid) of `data/cases/resistance/spheroid_dalembert.yaml` at U = {SPEED} m/s, slip walls everywhere and no turbulence
model, on the snappy family `{rel}` of `data/cases/resistance/spheroid_dalembert_mesh.yaml` (no prism layers;
each end refined one level beyond the hull cell in a box; grid 3 coarsest). d'Alembert: R_P = 0 and C_p = 1 at both
stagnation points. C_p max is the largest wall-face value (what the forces integrate: the cell value under the
zero-gradient pressure condition, carried to the wall by the curved-wall condition's dp/dn); fore and aft are the parts of R_P from x > L/2 and x < L/2; the order is
that of R_P against zero between a grid and the next coarser, with h the hull cell size, and beside it with Celik's
h = (V/N)^(1/3) of the whole grid (family.txt)."""]
    if rt:
        out.append(f"The viscous reference: R_T = {rt:.4g} N (spheroid_double_body.yaml, no-slip, k-omega SST).")
    for name, overrides, rows in tables:
        out.append(f"\n### {name}" + (f": the case with `{overrides}`" if overrides else ": the case as it is") + "\n")
        out.append("| grid | cells | hull cell (mm) | R_P (N) | " + ("R_P / R_T | " if rt else "") +
                   "C_P | order | order, (V/N)^(1/3) | C_p max, bow | C_p max, stern | fore (N) | aft (N) | "
                   "steps (settled) | CPU (s) |")
        out.append("| ---: | ---: | ---: | ---: | " + ("---: | " if rt else "") +
                   "---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: |")
        prev = None
        for r in rows:
            out.append(f"| {r['level']} | {r['cells']:,} | {1000 * r['hull']:.2f} | {r['R_P']:.4f} | " +
                       (f"{100 * r['R_P'] / rt:.2f}% | " if rt else "") +
                       f"{r['C_P']:.3e} | {order(prev, r, 'hull')} | {order(prev, r, 'h')} | {r['cp_bow']:.3f} | "
                       f"{r['cp_stern']:.3f} | {r['fore']:+.4f} | {r['aft']:+.4f} | {r['steps']} ({'yes' if r['settled'] else 'NO'}) | {r['cpu']:.0f} |")
            prev = r
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    main()
