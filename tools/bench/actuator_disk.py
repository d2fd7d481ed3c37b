#!/usr/bin/python3
"""Benchmark: the body-force propeller (actuator disk), section `actuator_disk`.

Runs the cases of tests/cfd/propulsion/actuator_disk_test.cc through its
GoogleTest binary and collects the lines it prints:

  - far wake of a uniformly loaded disk (C_Th = 1) in a uniform stream on the
    three grids of the family (refinement ratio sqrt 2), against actuator-disk
    momentum theory u_wake = U (sqrt(1 + C_Th) - 1), with the grid trend;
  - open water: the Hough-Ordway disk with the KP505 table at J = 0.6, 0.7,
    0.8 (n fixed), the Propeller's K_T at its corrected J against K_T(J_true),
    for the annular (default) and the closed-form (disk) momentum correction;
  - the CPU seconds of every run.

Usage: tools/bench/actuator_disk.py --test build/ci/tests/cfd/actuator_disk_test
       [--open-water-grids 0,1] [--write FILE]
(--write replaces the section in FILE, e.g. BENCHMARKS.md; without it the
section is printed.)
"""
import argparse
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pimple_vs_openfoam import write_or_print  # noqa: E402

NAME = "actuator_disk"
WAKE = re.compile(r"far_wake grid (\d): (\d+) cells, h = ([\d.]+) D, ([\d.]+) across D, share ([\d.]+), (\d+) steps, "
                  r"([\d.]+) CPU s: u_core = ([\d.]+), u_axis = ([\d.]+), theory ([\d.]+): core error ([-+\d.]+)%, "
                  r"axis ([-+\d.]+)%")
OPEN = re.compile(r"open_water grid (\d) J_true ([\d.]+): U_disk/U = ([\d.]+), J = ([\d.]+), K_T = ([\d.]+) "
                  r"\(K_T\(J_true\) = ([\d.]+)\): error ([-+\d.]+)%; the closed-form \(disk momentum\) correction would "
                  r"give J = ([\d.]+), K_T error ([-+\d.]+)%; ([\d.]+) CPU s")


def run(test, gtest_filter, env_extra):
    env = dict(os.environ, OMPI_MCA_ess_singleton_isolated="1", **env_extra)
    out = subprocess.run([test, f"--gtest_filter={gtest_filter}"], env=env, capture_output=True, text=True)
    return out.stdout


def section(wake, open_water):
    lines = [
        "## Body-force propeller (actuator disk)\n",
        "Produced by `tools/bench/actuator_disk.py` from `actuator_disk_test` (release build, one core). "
        "Quarter domain x in [-3D, 6D], y, z in [0, 4D] with symmetry planes through the axis (blockage of the full "
        "domain 1.2%), laminar, nu = 1e-4 m^2/s (Re_D = 1e4), Euler steps of 0.25 D/U to steady; core cells h on "
        "x in [-0.5D, 4D], r < 0.625D, stretched outside. Disk thickness 0.2D.\n",
        "### Far wake, uniform loading, C_Th = 1 (momentum theory u_wake / U = sqrt(2) - 1 = 0.41421)\n",
        "| grid | cells | h / D | cells across D | steps | CPU s | u_core / U (r < D/4, x in [2D, 4D]) | error | "
        "u on the axis row | error |",
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    for w in wake:
        lines.append(f"| {w[0]} | {w[1]} | {w[2]} | {w[3]} | {w[5]} | {w[6]} | {w[7]} | {w[10]}% | {w[8]} | {w[11]}% |")
    if len(wake) == 3:
        e21 = float(wake[1][7]) - float(wake[2][7])
        e32 = float(wake[0][7]) - float(wake[1][7])
        lines.append("")
        lines.append(f"Grid trend: e32 / e21 = {e32 / e21:.3f} at refinement ratio sqrt 2 (monotone when > 1).")
    lines += [
        "",
        "### Open water in CFD: Hough-Ordway disk (r_h/R = 0.2), KP505 table, n = 1/s, D = 1 m, thrust only "
        "(the symmetry planes carry no swirl)\n",
        "| grid | J_true | U_disk / U | J (annular correction) | K_T | K_T(J_true) | error | J (closed form) | "
        "error (closed form) | CPU s |",
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    for o in open_water:
        lines.append(f"| {o[0]} | {o[1]} | {o[2]} | {o[3]} | {o[4]} | {o[5]} | {o[6]}% | {o[7]} | {o[8]}% | {o[9]} |")
    return "\n".join(lines) + "\n\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--test", required=True, help="path to the actuator_disk_test binary")
    ap.add_argument("--open-water-grids", default="0", help="comma-separated grids of the open-water runs")
    ap.add_argument("--write", help="file whose actuator_disk section is replaced")
    args = ap.parse_args()
    wake = WAKE.findall(run(args.test, "*FarWakeFineGrid*", {"KELVIN_ACTUATOR_DISK_FINE": "1"}))
    open_water = []
    for g in args.open_water_grids.split(","):
        out = run(args.test, "*RecoversKTAtThreeJ*", {"KELVIN_ACTUATOR_DISK_OPEN_WATER_GRID": g})
        open_water += OPEN.findall(out)
    write_or_print(args.write, NAME, section(wake, open_water))


if __name__ == "__main__":
    main()
