#!/usr/bin/python3
"""Benchmark: the DTC's static drift on a three-grid family, section
`dtc_drift_gci` of BENCHMARKS.md (issue #25, acceptance 3).

Runs the campaign data/cases/captive_cfd/dtc_campaign.yaml (static drift at
0, 5 and 10 deg, each ended on the steady criterion of the ship-axes loads)
on each grid of the family of data/cases/mesh/dtc_snappy.yaml, identifies
the linear drift derivatives of each grid with `kelvin identify`, and
tabulates
  - per grid and angle: the settled X', Y', N' (mean from the settling time
    on), whether the run met its criterion, the change over its window;
  - the grid convergence of Y' and N' at 10 deg, of X' at 0 deg and of the
    identified Y_v, N_v (Celik et al. 2008: apparent order, Richardson
    extrapolation, fine-grid GCI) by `kelvin gci --values` on the values
    read from the three campaigns;
  - grid 1's derivatives identified from the settled parts against the same
    campaign analysed as before the steady criterion (every sample of the
    first 10 s after the ramp), issue #25 acceptance 4 (DTC part).

Usage:
  kelvin mesh data/cases/mesh/dtc_snappy.yaml --family 3 -o build/grids/doublebody_dtc
  tools/bench/dtc_drift_gci.py --kelvin build/ci/tools/kelvin [--jobs 2] [--write BENCHMARKS.md]
Finished runs are reused (the campaign resumes); the three campaigns take
about two CPU hours on this machine.
"""
import argparse
import datetime
import os
import re
import subprocess
import sys

import h5py
import numpy as np
import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pimple_vs_openfoam import write_or_print  # noqa: E402

NAME = "dtc_drift_gci"
ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
CAPTIVE = os.path.join(ROOT, "data", "cases", "captive_cfd")
ANGLES = (0.0, 5.0, 10.0)
FIXED_WINDOW = 10.0  # s after the ramp: the campaign window before the steady criterion (issue #25)


def grid_campaign(grids, grid, work):
    """Copies the campaign and its case into work/gridN with grid N's polyMesh."""
    d = os.path.join(work, f"grid{grid}")
    os.makedirs(d, exist_ok=True)
    mesh = os.path.abspath(os.path.join(grids, f"grid{grid}", "constant", "polyMesh"))
    with open(os.path.join(CAPTIVE, "dtc_case.yaml")) as f:
        case = re.sub(r"poly_mesh: [^}]*}", f"poly_mesh: {mesh}}}", f.read())
    # The case's dt is grid 1's; each grid takes the same Courant number (dt in proportion to h).
    h = family_h(grids)
    dt1 = float(re.search(r"time: \{dt: ([0-9.eE+-]+)\}", case).group(1))
    case = re.sub(r"time: \{dt: [0-9.eE+-]+\}", f"time: {{dt: {dt1 * h[grid] / h[1]:.4g}}}", case)
    with open(os.path.join(CAPTIVE, "dtc_campaign.yaml")) as f:
        campaign = f.read()
    campaign = campaign.replace("ship: ../../ships/dtc.yaml", "ship: " + os.path.join(ROOT, "data/ships/dtc.yaml"))
    campaign = re.sub(r"directory: [^\n]*", "directory: runs", campaign)
    for name, text in (("dtc_case.yaml", case), ("dtc_campaign.yaml", campaign)):
        with open(os.path.join(d, name), "w") as f:
            f.write(text)
    return d


def family_h(grids):
    """h = (V/N)^(1/3) per grid level from the family's family.txt."""
    h = {}
    with open(os.path.join(grids, "family.txt")) as f:
        for line in f:
            w = line.split()
            if w and w[0].isdigit():
                h[int(w[0])] = float(w[2])
    return h


def family_source(grids):
    """The mesh case the family was built from, as family.txt's header names it."""
    with open(os.path.join(grids, "family.txt")) as f:
        m = re.search(r"grid family of (\S+)", f.readline())
    return m.group(1) if m else "data/cases/mesh/dtc_snappy.yaml"


def run(cmd, log):
    env = dict(os.environ, OMPI_MCA_ess_singleton_isolated="1")
    with open(log, "w") as f:
        p = subprocess.run(cmd, env=env, stdout=f, stderr=subprocess.STDOUT)
    if p.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed; see {log}")


def settled_run(directory, channels=("X_prime", "Y_prime", "N_prime")):
    """Settled means of the captive channels and the criterion's record of one drift run."""
    with h5py.File(os.path.join(directory, "result.h5"), "r") as f:
        t = f["captive/time"][:]
        keep = t >= f.attrs["t_settle"] - 1e-9
        r = {k: float(np.mean(f["captive/" + k][:][keep])) for k in channels}
        r.update(settled=bool(f.attrs["settled"]), change=float(f.attrs["settle_change"]),
                 t_settle=float(f.attrs["t_settle"]), t_end=float(t[-1]), steps=len(t),
                 cpu=float(f.attrs["cpu_seconds"]), cells=int(f.attrs["cells"]))
    return r


def derivatives(path):
    """Y_v, N_v and their standard errors from a kelvin identify set (hull: and standard_errors: sections)."""
    with open(path) as f:
        d = yaml.safe_load(f)
    return {n: (float(d["hull"][n]), float(d["standard_errors"][n])) for n in ("Y_v", "N_v")}


def fixed_window_copy(src, dst, window):
    """A copy of a campaign file as a fixed-window campaign would have written it.

    Each steady run keeps its samples up to t_ramp + window and loses its
    settling record, so `kelvin identify` uses every sample after the ramp: the
    analysis before the steady criterion. The solver is deterministic, so the
    truncated samples are those a run ended at t_ramp + window computes.
    """
    with h5py.File(src, "r") as fin, h5py.File(dst + ".tmp", "w") as fout:
        for k, v in fin.attrs.items():
            fout.attrs[k] = v
        fin.copy("ship", fout)
        for name, run in fin["runs"].items():
            g = fout.create_group("runs/" + name)
            for k, v in run.attrs.items():
                if k not in ("t_settle", "settled", "settle_change"):
                    g.attrs[k] = v
            t = run["time"][:]
            keep = t <= float(run.attrs["t_ramp"]) + window + 1e-9 if "t_settle" in run.attrs else slice(None)
            for ds_name, ds in run.items():
                d = g.create_dataset(ds_name, data=ds[:][keep], maxshape=(None,) + ds.shape[1:], chunks=True)
                for k, v in ds.attrs.items():
                    d.attrs[k] = v
    os.replace(dst + ".tmp", dst)


def hull_coefficients(path):
    with open(path) as f:
        return {k: float(v) for k, v in yaml.safe_load(f)["hull"].items() if v is not None}


def fixed_against_settled(kelvin, d):
    """Grid 1's derivatives from the settled parts against a fixed 10 s window (issue #25 acceptance 4, DTC)."""
    fixed_h5 = os.path.join(d, "fixed_window.h5")
    fixed_window_copy(os.path.join(d, "runs", "dtc_cfd.h5"), fixed_h5, FIXED_WINDOW)
    fixed_yaml = os.path.join(d, "derivatives_fixed_window.yaml")
    run([kelvin, "identify", fixed_h5, "-o", fixed_yaml], os.path.join(d, "identify_fixed_window.log"))
    fixed, settled = hull_coefficients(fixed_yaml), hull_coefficients(os.path.join(d, "derivatives.yaml"))
    lines = ["", f"Grid 1's campaign analysed as before the steady criterion (every sample from the ramp to "
             f"{FIXED_WINDOW:g} s after it, the samples the earlier fixed window computed) and on the settled "
             "parts:\n", "| coefficient | fixed window | settled | settled / fixed - 1 |", "| --- | ---: | ---: | ---: |"]
    for k in sorted(set(fixed) | set(settled)):
        f, st = fixed.get(k, 0.0), settled.get(k, 0.0)
        if f == 0.0 and st == 0.0:
            continue  # not excited by a static-drift matrix
        move = f"{100 * (st / f - 1):+.1f}%" if f and st else "-"
        lines.append(f"| {k} | {f'{f:.6g}' if f else 'dropped'} | {f'{st:.6g}' if st else 'dropped'} | {move} |")
    lines.append("\n'dropped': kelvin identify held the term at 0 (standard error above 25% of the value).")
    return lines + [""]


def kelvin_gci(kelvin, grids, work, quantities, settled):
    """The GCI of each quantity by `kelvin gci --values` (Celik et al. 2008, the same code as a case study)."""
    values = os.path.join(work, "gci_values.yaml")
    with open(values, "w") as f:
        yaml.safe_dump({"outputs": {k: [float(x) for x in v] for k, v in quantities.items()},
                        "settled": [bool(x) for x in settled]}, f, sort_keys=False)
    stem = os.path.join(work, "gci")
    run([kelvin, "gci", "--grids", grids, "--values", values, "--report", stem], os.path.join(work, "gci.log"))
    with open(stem + ".yaml") as f:
        return yaml.safe_load(f)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kelvin", required=True)
    ap.add_argument("--grids", default=os.path.join(ROOT, "build", "grids", "doublebody_dtc"))
    ap.add_argument("--work", default=os.path.join(ROOT, "results", "dtc_drift_gci"))
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--grid", type=int, action="append", help="run only this grid (repeatable); the table needs all")
    ap.add_argument("--write", help="replace the section in this file (e.g. BENCHMARKS.md)")
    ap.add_argument("--section", default=NAME,
                    help=f"the BENCHMARKS.md section to write (default {NAME}; another family gets its own)")
    a = ap.parse_args()

    grids = a.grid or [3, 2, 1]
    for g in grids:
        d = grid_campaign(a.grids, g, a.work)
        run([a.kelvin, "captive", os.path.join(d, "dtc_campaign.yaml"), "--jobs", str(a.jobs), "--no-progress"],
            os.path.join(d, "captive.log"))
        run([a.kelvin, "identify", os.path.join(d, "runs", "dtc_cfd.h5"), "-o", os.path.join(d, "derivatives.yaml")],
            os.path.join(d, "identify.log"))
        print(f"grid {g}: done", file=sys.stderr)
    if a.grid and len(a.grid) < 3:
        return

    res = {g: {b: settled_run(os.path.join(a.work, f"grid{g}", "runs", f"drift_{b:+.1f}deg")) for b in ANGLES}
           for g in (1, 2, 3)}
    der = {g: derivatives(os.path.join(a.work, f"grid{g}", "derivatives.yaml")) for g in (1, 2, 3)}
    quantities = {"X_prime_0deg": [res[g][0.0]["X_prime"] for g in (1, 2, 3)],
                  "Y_prime_10deg": [res[g][10.0]["Y_prime"] for g in (1, 2, 3)],
                  "N_prime_10deg": [res[g][10.0]["N_prime"] for g in (1, 2, 3)],
                  "Y_v": [der[g]["Y_v"][0] for g in (1, 2, 3)],
                  "N_v": [der[g]["N_v"][0] for g in (1, 2, 3)]}
    settled = [all(res[g][b]["settled"] for b in ANGLES) for g in (1, 2, 3)]
    report = kelvin_gci(a.kelvin, a.grids, a.work, quantities, settled)
    out = report["outputs"]
    h = {r["level"]: r["h"] for r in report["grids"]}
    source = family_source(a.grids)
    lines = [
        f"## DTC static drift on three grids of `{source}`, with GCI (issue #25, acceptance 3)\n",
        f"Run by `tools/bench/dtc_drift_gci.py` on {datetime.datetime.utcnow():%Y-%m-%d %H:%M} UTC (2 shared "
        "cores). The campaign `data/cases/captive_cfd/dtc_campaign.yaml` (DTC model 1:59.407 at 1.668 m/s, fixed "
        "at the design waterline, k-omega SST with wall functions, the linearized free surface, the grid moving "
        f"with the hull) on each grid of `{source} --family 3`, the time step in proportion to h "
        "(the same Courant number on every grid; 0.1 s on grid 3). Each drift run ends when "
        "the ship-axes loads change by less than the campaign's tolerance over its window; the values are the "
        "means from the settling time on. Primes: X' = X / (rho/2 U^2 Lpp d), N' = N / (rho/2 U^2 Lpp^2 d).\n",
        "| grid | cells | h (m) | drift (deg) | X' | Y' | N' | settled | change over the window | t_settle (s) "
        "| steps | CPU (s) |",
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | :---: | ---: | ---: | ---: | ---: |",
    ]
    for g in (1, 2, 3):
        for b in ANGLES:
            r = res[g][b]
            lines.append(f"| {g} | {r['cells']} | {h[g]:.4f} | {b:g} | {r['X_prime']:.5f} | "
                         f"{r['Y_prime']:.5f} | {r['N_prime']:.5f} | {'yes' if r['settled'] else '**NO**'} | "
                         f"{100 * r['change']:.2f}% | {r['t_settle']:.1f} | {r['steps']} | {r['cpu']:.0f} |")
    lines += ["", "| quantity | grid 3 | grid 2 | grid 1 | convergence | p | extrapolated | GCI21 (fine grid) |",
              "| --- | ---: | ---: | ---: | --- | ---: | ---: | ---: |"]
    for name, phi in quantities.items():
        c = out[name]
        lines.append(f"| {name} | {phi[2]:.5f} | {phi[1]:.5f} | {phi[0]:.5f} | {c['convergence']} (R {c['R']:.3f}) | "
                     f"{c['p']:.2f} | {c['extrapolated']:.5f} | {100 * c['gci_fine']:.2f}% |")
    se = {n: der[1][n][1] for n in ("Y_v", "N_v")}
    lines += ["", f"Grid 1's fit standard errors (kelvin identify): Y_v {se['Y_v']:.2g}, N_v {se['N_v']:.2g}.\n"]
    lines += fixed_against_settled(a.kelvin, os.path.join(a.work, "grid1"))
    write_or_print(a.write, a.section, "\n".join(lines))


if __name__ == "__main__":
    main()
