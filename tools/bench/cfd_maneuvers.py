#!/usr/bin/python3
"""Benchmark: IMO maneuvers in free-running CFD, section `cfd_maneuvers` of BENCHMARKS.md.

Flies data/cases/free_running/wigley_turning.yaml (the body-force propeller
and rudder of data/ships/wigley.yaml, steered by the simulator's controller)
as 35 deg turning circles and 10/10 and 20/20 zig-zags to both sides, with
the propeller's swirl on and off. Tabulates the metrics of each pair of
sides (the hull is symmetric: without swirl they must agree) and the cost of
each run (CPU seconds of `kelvin run`, from the child's resource usage)
against `kelvin simulate` flying the same maneuvers with the ship file's
MMG model.

Usage: tools/bench/cfd_maneuvers.py --kelvin build/ci/tools/kelvin [--jobs 2]
       [--work build/bench/cfd_maneuvers] [--write BENCHMARKS.md]
"""
import argparse
import os
import re
import subprocess
import sys
import time

import h5py

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pimple_vs_openfoam import write_or_print  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
CASE = os.path.join(ROOT, "data/cases/free_running/wigley_turning.yaml")
SHIP = os.path.join(ROOT, "data/ships/wigley.yaml")
MANEUVERS = ["turning:35", "zigzag:10/10", "zigzag:20/20"]
METRICS = {"turning": ["advance_over_L", "tactical_diameter_over_L", "steady_diameter_over_L", "steady_rate",
                       "time_to_90"],
           "zigzag": ["first_overshoot", "second_overshoot", "first_overshoot_time", "second_overshoot_time"]}


def run_name(maneuver, side, swirl):
    return f"{maneuver.replace(':', '_').replace('/', '_')}_{side}_{'swirl' if swirl else 'noswirl'}"


def case_text(maneuver, side, swirl):
    """The case with absolute paths, the maneuver and the propeller's swirl."""
    with open(CASE) as f:
        text = f.read()
    case_dir = os.path.dirname(CASE)
    text = re.sub(r"poly_mesh: (\S+)}", lambda m: f"poly_mesh: {os.path.normpath(os.path.join(case_dir, m.group(1)))}}}",
                  text)
    text = text.replace("ship: ../../ships/wigley.yaml", f"ship: {SHIP}")
    if 'kind: "turning:35:stbd"' not in text or "  thickness: 0.25\n" not in text:
        sys.exit(f"{CASE}: no 'kind: \"turning:35:stbd\"' or propeller 'thickness: 0.25' to replace")
    new = text.replace('kind: "turning:35:stbd"', f'kind: "{maneuver}:{side}"')
    if not swirl:
        new = new.replace("  thickness: 0.25\n", "  thickness: 0.25\n  swirl: false\n", 1)
    return new


def launch(kelvin, work, name, text):
    d = os.path.join(work, name)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, "case.yaml"), "w") as f:
        f.write(text)
    env = dict(os.environ, OMPI_MCA_ess_singleton_isolated="1")
    log = open(os.path.join(d, "kelvin_run.log"), "w")
    return subprocess.Popen([kelvin, "run", os.path.join(d, "case.yaml"), "--no-progress", "-o", os.path.join(d, "out")],
                            env=env, stdout=log, stderr=subprocess.STDOUT)


def run_all(kelvin, work, runs, jobs):
    """Runs the cases `jobs` at a time; returns CPU seconds per run (children's rusage)."""
    pending, running, cpu = list(runs), {}, {}
    while pending or running:
        while pending and len(running) < jobs:
            name, text = pending.pop(0)
            running[launch(kelvin, work, name, text).pid] = name
        pid, status, usage = os.wait4(-1, 0)
        name = running.pop(pid, None)
        if name is None:
            continue
        if os.waitstatus_to_exitcode(status) != 0:
            sys.exit(f"{name}: kelvin run failed; see {os.path.join(work, name, 'kelvin_run.log')}")
        cpu[name] = usage.ru_utime + usage.ru_stime
        print(f"{name}: {cpu[name]:.1f} CPU s", file=sys.stderr)
    return cpu


def result(work, name):
    with h5py.File(os.path.join(work, name, "out", "maneuver.h5"), "r") as h:
        metrics = {k: float(h["metrics"][k][0]) for k in h["metrics"]}
        t = h["trajectory/time"][:]
        steps = len(t)
    with open(os.path.join(work, name, "kelvin_run.log")) as f:
        log = f.read()
    cells = int(re.search(r"cells (\d+)", log).group(1))
    return metrics, t[-1], steps, cells


def simulator_cpu(kelvin, work):
    """CPU seconds of kelvin simulate flying all the maneuvers at 1 m/s (one process)."""
    args = [kelvin, "simulate", SHIP, "--speed", "1.0", "-o", os.path.join(work, "simulate")]
    for m in MANEUVERS:
        for side in ("stbd", "port"):
            args += ["-m", f"{m}:{side}"]
    t0 = os.times()
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
    t1 = os.times()
    return (t1.children_user - t0.children_user) + (t1.children_system - t0.children_system), 2 * len(MANEUVERS)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kelvin", required=True, help="path to the kelvin program")
    ap.add_argument("--jobs", type=int, default=2, help="runs at a time (default 2)")
    ap.add_argument("--work", default=os.path.join(ROOT, "build/bench/cfd_maneuvers"))
    ap.add_argument("--write", help="replace the section in this file (e.g. BENCHMARKS.md)")
    args = ap.parse_args()
    if args.jobs < 1:
        sys.exit(f"--jobs {args.jobs}: expected at least 1")
    runs = [(run_name(m, side, swirl), case_text(m, side, swirl))
            for swirl in (False, True) for m in MANEUVERS for side in ("stbd", "port")]
    start = time.time()
    cpu = run_all(args.kelvin, args.work, runs, args.jobs)
    sim_cpu, sim_runs = simulator_cpu(args.kelvin, args.work)

    out = ["## cfd_maneuvers: IMO maneuvers in free-running CFD (issue #21, acceptances 2 and 5)", "",
           f"`tools/bench/cfd_maneuvers.py --jobs {args.jobs}`: `data/cases/free_running/wigley_turning.yaml` (the "
           "1 m Wigley at 1 m/s on the quickstart's captive grid, the body-force propeller at n = 59.79 1/s and the "
           "body-force rudder of `data/ships/wigley.yaml`, both assumed; dt 0.04 s), steered by the simulator's "
           "maneuver controller. The disk and the blade are about 2 cells across: these runs measure the chain, "
           f"its symmetry and its cost, not converged maneuvering. {len(runs)} runs, {args.jobs} at a time, "
           f"{time.time() - start:.0f} s wall.", ""]
    for swirl in (False, True):
        out += [f"### Propeller swirl {'on' if swirl else 'off'}", "",
                "| maneuver | metric | starboard | port | port / starboard - 1 |", "| --- | --- | ---: | ---: | ---: |"]
        for m in MANEUVERS:
            s, _, _, _ = result(args.work, run_name(m, "stbd", swirl))
            p, _, _, _ = result(args.work, run_name(m, "port", swirl))
            for k in METRICS[m.split(":")[0]]:
                rel = p[k] / s[k] - 1 if s[k] != 0 else float("nan")
                out.append(f"| {m} | {k} | {s[k]:.4f} | {p[k]:.4f} | {100 * rel:+.2f}% |")
        out.append("")
    out += ["### Cost", "", "| run | cells | steps | simulated (s) | CPU (s) | CPU-h / Mcell / simulated s |",
            "| --- | ---: | ---: | ---: | ---: | ---: |"]
    total = 0.0
    for name, _ in runs:
        _, t_end, steps, cells = result(args.work, name)
        total += cpu[name]
        out.append(f"| {name} | {cells} | {steps} | {t_end:.2f} | {cpu[name]:.1f} | "
                   f"{cpu[name] / 3600 / (cells / 1e6) / t_end:.4f} |")
    per_sim = sim_cpu / sim_runs
    out += ["", f"`kelvin simulate` (CVODE, the ship file's MMG model) flew the {sim_runs} maneuvers in {sim_cpu:.2f} "
            f"CPU s in one process, start-up included ({per_sim:.3f} s each); the {len(runs)} CFD runs took "
            f"{total:.0f} CPU s ({total / len(runs):.1f} s each): the CFD costs about {total / len(runs) / per_sim:.0f} "
            "times the surrogate per maneuver on this 5k-cell grid, and the ratio grows with the cells. No published "
            "CPU cost of a resolved-propeller free-running CFD maneuver was found in the search corpora, so none is "
            "compared.", ""]
    write_or_print(args.write, "cfd_maneuvers", "\n".join(out))


if __name__ == "__main__":
    main()
