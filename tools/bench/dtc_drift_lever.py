#!/usr/bin/python3
"""Benchmark: where the DTC's lateral force at drift acts, section
`dtc_drift_lever` of BENCHMARKS.md (issue #25, "the lateral force of the aft
body").

The lever of the lateral force about midship, N' / Y' (in Lpp; N' on Lpp^2 d,
Y' on Lpp d), and the pressure share of Y, from the settled static-drift
runs of tools/bench/dtc_drift_gci.py on the three grids of the dtc_snappy
family (the grid factor), and from the same 10 deg run on grid 3 as a double
body (z = 0 a slip plane instead of the linearized free surface: the free
surface's factor).

Usage (after dtc_drift_gci.py has run the three grids):
  tools/bench/dtc_drift_lever.py --kelvin build/ci/tools/kelvin [--write BENCHMARKS.md]
"""
import argparse
import datetime
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from dtc_drift_gci import ROOT, grid_campaign, run, settled_run  # noqa: E402
from pimple_vs_openfoam import write_or_print  # noqa: E402

NAME = "dtc_drift_lever"
DOUBLE_BODY_FS = "  freeSurface: {U: {type: slip}, p: {type: zeroGradient}}\n"
# The settled ship-axes loads read from each drift run: totals, pressure and viscous parts.
CHANNELS = ("Y_prime", "N_prime", "Y", "Y_pressure", "Y_viscous", "N", "N_pressure", "N_viscous")


def double_body_campaign(grids, grid, work):
    """Grid `grid`'s campaign at 10 deg with the free surface replaced by a slip plane."""
    d = grid_campaign(grids, grid, work)
    case = os.path.join(d, "dtc_case.yaml")
    text = open(case).read()
    text = re.sub(r"  freeSurface:\n(    .*\n)+", DOUBLE_BODY_FS, text)
    if DOUBLE_BODY_FS not in text:
        sys.exit(f"{case}: could not replace the freeSurface boundary")
    open(case, "w").write(text)
    campaign = os.path.join(d, "dtc_campaign.yaml")
    text = re.sub(r"static_drift_deg: \[[^]]*\]", "static_drift_deg: [10]", open(campaign).read())
    open(campaign, "w").write(text)
    return d


def row(label, r):
    lever = r["N_prime"] / r["Y_prime"]
    return (f"| {label} | {r['Y_prime']:.5f} | {r['N_prime']:.5f} | {lever:.3f} | "
            f"{r['Y_pressure'] / r['Y']:.3f} | {r['N_pressure'] / r['N']:.3f} | {'yes' if r['settled'] else '**NO**'} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kelvin", required=True)
    ap.add_argument("--grids", default=os.path.join(ROOT, "build", "grids", "doublebody_dtc"))
    ap.add_argument("--gci-work", default=os.path.join(ROOT, "results", "dtc_drift_gci"))
    ap.add_argument("--work", default=os.path.join(ROOT, "results", "dtc_drift_lever"))
    ap.add_argument("--double-body-grid", type=int, default=3)
    ap.add_argument("--write", help="replace the section in this file (e.g. BENCHMARKS.md)")
    a = ap.parse_args()

    g = a.double_body_grid
    d = double_body_campaign(a.grids, g, a.work)
    run([a.kelvin, "captive", os.path.join(d, "dtc_campaign.yaml"), "--no-progress"], os.path.join(d, "captive.log"))
    lfs = {k: {b: settled_run(os.path.join(a.gci_work, f"grid{k}", "runs", f"drift_{b:+.1f}deg"), CHANNELS) for b in (5.0, 10.0)}
           for k in (1, 2, 3)}
    db = settled_run(os.path.join(d, "runs", "drift_+10.0deg"), CHANNELS)
    lines = [
        "## Where the DTC's lateral force at drift acts (issue #25, the aft body's lateral force)\n",
        f"Run by `tools/bench/dtc_drift_lever.py` on {datetime.datetime.utcnow():%Y-%m-%d %H:%M} UTC from the settled "
        "static-drift runs of `dtc_drift_gci` (above) and one double-body run. Lever about midship N'/Y' in Lpp "
        "(positive: ahead of midship); the pressure shares are of the settled totals.\n",
        "| run | Y' | N' | N'/Y' (Lpp) | Y_pressure / Y | N_pressure / N | settled |",
        "| --- | ---: | ---: | ---: | ---: | ---: | :---: |",
    ]
    for k in (3, 2, 1):
        for b in (5.0, 10.0):
            lines.append(row(f"grid {k}, {b:g} deg, free surface", lfs[k][b]))
    lines.append(row(f"grid {g}, 10 deg, double body", db))
    ref = lfs[g][10.0]
    lines += ["", f"On grid {g} at 10 deg the free surface moves Y' by {100 * (ref['Y_prime'] / db['Y_prime'] - 1):+.1f}% "
              f"and N' by {100 * (ref['N_prime'] / db['N_prime'] - 1):+.1f}% against the double body; from grid 3 to "
              f"grid 1 the 10 deg lever goes {lfs[3][10.0]['N_prime'] / lfs[3][10.0]['Y_prime']:.3f} -> "
              f"{lfs[2][10.0]['N_prime'] / lfs[2][10.0]['Y_prime']:.3f} -> "
              f"{lfs[1][10.0]['N_prime'] / lfs[1][10.0]['Y_prime']:.3f} Lpp.\n"]
    write_or_print(a.write, NAME, "\n".join(lines))


if __name__ == "__main__":
    main()
