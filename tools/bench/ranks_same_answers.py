#!/usr/bin/env python3
"""Same answers on 1, 2 and 4 MPI ranks on the Wigley cases (issue 23, acceptance 1).

Two cases of the quickstart, each run by `kelvin run` serially and with `--np 2` and `--np 4`
(4 oversubscribed on a 2-core machine):

- resistance: data/cases/resistance/wigley_quick.yaml (the coarse Wigley at Fn 0.316, SST, linearized
  free surface, rigid-lid start, resistance report);
- pmm: data/cases/captive_cfd/wigley_quick_case.yaml with a pure-yaw motion of the quick campaign
  (r' = 0.2 at omega' = 1.2, 96 steps per period; captive loads every step);
- turning (tight only): the free-running 35 deg turn of data/cases/free_running/wigley_turning.yaml (the
  body-force propeller and rudder, the simulator's maneuver controller) over its first 6 s.

Each is run twice:

- "tight": a fixed number of steps with every linear solver at relative tolerance 1e-10 (the steady
  criterion off); the hull force (pressure and viscous, or X, Y, N of the PMM run) at every step is compared
  with the serial run's, relative to its largest value over the run;
- "own": the case with its own tolerances, to its steady state (resistance: C_T) or over its periods (pmm:
  the first harmonics of Y and N over the last period, Fourier projections of the captive loads at the
  motion's frequency, the quantities `kelvin identify` fits the linear yaw derivatives to).

The grids come from `kelvin mesh` (wigley_quick_mesh.yaml files) into <work>/grids. A grid of about 5k
cells on 4 ranks is below the 2,000 cells per rank kelvin asks by default; the cases here set
partition.min_cells_per_rank to 500 (this is a correctness comparison, not a speed one).

Usage: tools/bench/ranks_same_answers.py --kelvin build/ci/tools/kelvin [--ranks 1 2 4] [--write BENCHMARKS.md]
"""
import argparse
import datetime
import math
import os
import re
import subprocess
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pimple_vs_openfoam import write_or_print  # noqa: E402

NAME = "ranks_same_answers"
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TIGHT = 1.0e-10

# Pure yaw of wigley_quick_campaign.yaml: L = 1 m, U = 1 m/s, omega' = 1.2, r' = 0.2.
OMEGA = 1.2
PERIOD = 2 * math.pi / OMEGA
YAW_AMPLITUDE_DEG = math.degrees(0.2 / 1.2)
STEPS_PER_PERIOD = 96


def mesh(kelvin, mesh_yaml, out):
    """The grid of `mesh_yaml` written into `out` (reused when it is there)."""
    poly = os.path.join(out, "constant", "polyMesh")
    if not os.path.isdir(poly):
        subprocess.run([kelvin, "mesh", mesh_yaml, "-o", out], check=True, capture_output=True, text=True)
    return poly


def edit(text, poly, directory, tight, steps=None):
    """The case text with its grid, output directory, partition and (tight) tolerances set."""
    text = re.sub(r"mesh: \{poly_mesh: [^}]*\}", f"mesh: {{poly_mesh: {poly}}}", text)
    text = re.sub(r"directory: [^,}]*", f"directory: {directory}", text)
    text += "\npartition: {min_cells_per_rank: 500}\n"
    if tight:
        text = re.sub(r"relative_tolerance: [0-9.eE+-]+", f"relative_tolerance: {TIGHT:g}", text)
        text = re.sub(r"final_relative_tolerance: [0-9.eE+-]+", f"final_relative_tolerance: {TIGHT:g}", text)
        text = re.sub(r"tolerance: 1\.0e-3", "tolerance: 1.0e-14", text)  # the steady criterion never stops it
        text = text.replace("turbulence:\n", f"turbulence:\n  solver: {{relative_tolerance: {TIGHT:g}}}\n")
    return text


def resistance_case(poly, directory, tight, steps):
    text = open(os.path.join(ROOT, "data/cases/resistance/wigley_quick.yaml")).read()
    text = edit(text, poly, directory, tight)
    if tight:
        text = re.sub(r"end: 200\.0", f"end: {0.5 * steps}", text)
    return text


def pmm_case(poly, directory, tight, steps):
    text = open(os.path.join(ROOT, "data/cases/captive_cfd/wigley_quick_case.yaml")).read()
    text = edit(text, poly, directory, tight)
    dt = PERIOD / STEPS_PER_PERIOD
    periods = 3  # one ramp period, two sampled (sampling.ramp_periods 2 of the campaign: the last is used)
    text = text.replace("time: {dt: 0.04}", f"time: {{dt: {dt!r}" + (f", end: {dt * steps!r}}}" if tight else "}"))
    motion = (f"motion: {{kind: pure_yaw, speed: 1.0, yaw_amplitude_deg: {YAW_AMPLITUDE_DEG!r}, period: {PERIOD!r}, "
              f"ramp_time: {PERIOD!r}, centre: [0.5, 0, 0]" + ("" if tight else f", periods: {periods}") + "}\n")
    text = text.replace("output: {", "reference: {speed: 1.0, direction: [-1, 0, 0], length: 1.0, draft: 0.0625}\n"
                        + motion + "output: {")
    text = text.replace("forces: [hull]}", "forces: [hull], captive: true}")
    return text


def turning_case(poly, directory, tight, steps):
    """The free-running 35 deg turn of data/cases/free_running/wigley_turning.yaml (body-force propeller and
    rudder, the simulator's maneuver controller), cut to `steps` steps of 0.04 s."""
    path = os.path.join(ROOT, "data/cases/free_running/wigley_turning.yaml")
    text = open(path).read().replace("ship: ../../ships/wigley.yaml",
                                     "ship: " + os.path.join(ROOT, "data/ships/wigley.yaml"))
    text = edit(text, poly, directory, tight)
    return text.replace("end: 80.0", f"end: {0.04 * steps!r}")


def run(kelvin, case_text, work, name, ranks):
    d = os.path.join(work, f"{name}_np{ranks}")
    os.makedirs(d, exist_ok=True)
    case = os.path.join(d, "case.yaml")
    with open(case, "w") as f:
        f.write(case_text.replace("@OUT@", os.path.join(d, "out")))
    cmd = [kelvin, "run", case] if ranks == 1 else [kelvin, "run", "--np", str(ranks), case]
    env = dict(os.environ, OMPI_MCA_rmaps_base_oversubscribe="1", OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    out = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if out.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed:\n{out.stdout[-2000:]}\n{out.stderr[-3000:]}")
    return os.path.join(d, "out")


def step_series(out, kind):
    """Per step, the forces compared: the hull's pressure and viscous force vectors (N), or the captive X, Y
    and N, each an array of one row per step."""
    with h5py.File(os.path.join(out, "history.h5")) as h:
        if kind == "turning":  # every column on its own (their units differ)
            names = ["body/trajectory", "body/velocity", "body/hull_load", "body/actuator_load", "rudder/state",
                     "propeller/state"]
            return {f"{n}[{k}]": np.asarray(h[n][:])[:, k:k + 1] for n in names for k in range(3)
                    if np.any(np.asarray(h[n][:])[:, k] != 0)}
        else:
            names = ["captive/X", "captive/Y", "captive/N"] if kind == "pmm" else ["forces/hull/pressure",
                                                                                  "forces/hull/viscous"]
        return {n: np.asarray(h[n][:]).reshape(len(h[n]), -1) for n in names}


def mismatch(a, b):
    """Largest difference at any step, |a - b| of the force vector over the largest |b| of the run."""
    return max(np.max(np.linalg.norm(a[n] - b[n], axis=1)) / np.max(np.linalg.norm(b[n], axis=1)) for n in b)


def harmonics(out):
    """First harmonics (amplitude of the in-phase and quadrature parts) of Y and N over the last period."""
    with h5py.File(os.path.join(out, "history.h5")) as h:
        t = h["time"][:]
        loads = {k: h[f"captive/{k}"][:] for k in ("Y", "N")}
    last = t > t[-1] - PERIOD * (1 - 0.5 / STEPS_PER_PERIOD)
    res = {}
    for k, v in loads.items():
        s = 2 * np.mean(v[last] * np.sin(OMEGA * t[last]))
        c = 2 * np.mean(v[last] * np.cos(OMEGA * t[last]))
        res[k] = (s, c)
    return res


def c_t(out):
    with h5py.File(os.path.join(out, "resistance.h5")) as h:
        return float(h["C_T"][0]), int(h["converged_step"][0])


def tight_rows(kelvin, work, ranks, name, make, steps):
    rows = []
    series = {}
    for n in ranks:
        series[n] = step_series(run(kelvin, make(steps), work, f"{name}_tight", n), name)
    base = series[ranks[0]]
    steps = len(next(iter(base.values())))
    for n in ranks[1:]:
        s = series[n]
        if any(s[k].shape != base[k].shape for k in base):
            sys.exit(f"{name}: another number of steps on {n} ranks than serially")
        rows.append((name, n, steps, mismatch(s, base)))
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kelvin", required=True)
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2, 4])
    ap.add_argument("--steps", type=int, default=40, help="steps of the tight runs (default 40)")
    ap.add_argument("--turning-steps", type=int, default=150,
                    help="steps of 0.04 s of the free-running turn (default 150: release at 2 s, rudder at 5 s)")
    ap.add_argument("--work", default=None)
    ap.add_argument("--write", help="BENCHMARKS.md to update (default: print the section)")
    a = ap.parse_args()
    kelvin = os.path.abspath(a.kelvin)
    work = a.work or tempfile.mkdtemp(prefix="kelvin_ranks_")
    os.makedirs(work, exist_ok=True)
    grids = os.path.join(work, "grids")
    res_poly = mesh(kelvin, os.path.join(ROOT, "data/cases/resistance/wigley_quick_mesh.yaml"),
                    os.path.join(grids, "wigley_quick"))
    pmm_poly = mesh(kelvin, os.path.join(ROOT, "data/cases/captive_cfd/wigley_quick_mesh.yaml"),
                    os.path.join(grids, "wigley_captive_quick"))

    tight = []
    tight += tight_rows(kelvin, work, a.ranks, "resistance",
                        lambda s: resistance_case(res_poly, "@OUT@", True, s), a.steps)
    tight += tight_rows(kelvin, work, a.ranks, "pmm", lambda s: pmm_case(pmm_poly, "@OUT@", True, s), a.steps)
    tight += tight_rows(kelvin, work, a.ranks, "turning",
                        lambda s: turning_case(pmm_poly, "@OUT@", True, s), a.turning_steps)
    for r in tight:
        print(f"tight {r[0]} {r[1]} ranks: {r[2]} steps, max difference {r[3]:.2e} of the largest", flush=True)

    own = {}
    for n in a.ranks:
        ct, step = c_t(run(kelvin, resistance_case(res_poly, "@OUT@", False, 0), work, "resistance_own", n))
        hm = harmonics(run(kelvin, pmm_case(pmm_poly, "@OUT@", False, 0), work, "pmm_own", n))
        own[n] = (ct, step, hm)
        print(f"own {n} ranks: C_T {ct:.8e} (converged at step {step}), Y1 {hm['Y']}, N1 {hm['N']}", flush=True)

    base = own[a.ranks[0]]
    lines = [
        "## ranks_same_answers: the Wigley cases on 1, 2 and 4 MPI ranks (issue 23, acceptance 1)",
        "",
        f"Run on {datetime.datetime.utcnow():%Y-%m-%d %H:%M} UTC by `tools/bench/ranks_same_answers.py` on this "
        "2-core machine (4 ranks oversubscribed). Resistance: `data/cases/resistance/wigley_quick.yaml` (coarse "
        "Wigley, Fn 0.316, SST, linearized free surface with rigid-lid start, beach and limiter). PMM: "
        "`data/cases/captive_cfd/wigley_quick_case.yaml` in pure yaw, r' = 0.2 at omega' = 1.2, 96 steps per "
        "period (the quick campaign's run), captive loads. Both grids from `kelvin mesh`; "
        "`partition.min_cells_per_rank` lowered to 500 so that the 5k-cell captive grid goes on 4 ranks.",
        "",
        f"Tight: {a.steps} steps with every linear solver (momentum, pressure, k and omega) at relative tolerance "
        f"{TIGHT:g}; the largest difference at any step against the serial run of the hull's pressure force and "
        "viscous force vectors (resistance) or of X, Y and N (PMM), each relative to its largest magnitude over "
        "the run; for the free-running turn (150 steps: release at 2 s, rudder executed at 5 s) each column of the "
        "body's trajectory, velocities, hull and actuator loads, and of the rudder (angle, order, normal force) and "
        "propeller (rate, thrust, torque) states relative to its largest value. Acceptance: 1e-8.",
        "",
        "| case | ranks | steps | max difference |",
        "|---|---:|---:|---:|",
    ]
    lines += [f"| {r[0]} | {r[1]} | {r[2]} | {r[3]:.2e} |" for r in tight]
    lines += [
        "",
        "Own tolerances: the resistance case to its steady criterion (C_T), the PMM run over 3 periods (the "
        "first harmonics of Y and N over the last period, in phase with sin and cos of omega t). Differences "
        "relative to the serial value (for a harmonic, to the amplitude of the serial harmonic). Acceptance: "
        "0.05%.",
        "",
        "| ranks | C_T | converged at step | C_T diff | Y harmonic diff | N harmonic diff |",
        "|---:|---:|---:|---:|---:|---:|",
    ]
    for n in a.ranks:
        ct, step, hm = own[n]
        d_ct = abs(ct - base[0]) / abs(base[0])

        def hdiff(k):
            b = base[2][k]
            return math.hypot(hm[k][0] - b[0], hm[k][1] - b[1]) / math.hypot(*b)

        lines.append(f"| {n} | {ct:.6e} | {step} | {100 * d_ct:.2e}% | {100 * hdiff('Y'):.2e}% | "
                     f"{100 * hdiff('N'):.2e}% |")
    lines += [""]
    write_or_print(a.write, NAME, "\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
