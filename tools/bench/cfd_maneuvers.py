#!/usr/bin/python3
"""Benchmark: IMO maneuvers in free-running CFD, sections `cfd_maneuvers` (Wigley) and
`cfd_maneuvers_dtc` of BENCHMARKS.md.

Flies a free-running case (by default data/cases/free_running/wigley_turning.yaml:
the body-force propeller and rudder of data/ships/wigley.yaml, steered by the
simulator's controller) as the given maneuvers (by default 35 deg turning
circles and 10/10 and 20/20 zig-zags) to both sides, with the propeller's
swirl on and off (or only one of them). Tabulates the metrics of each pair
of sides (a symmetric hull without swirl must agree) and the cost of each run
(CPU seconds of `kelvin run`, from the child's resource usage) against
`kelvin simulate` flying the same maneuvers with the ship file's MMG model.

Usage: tools/bench/cfd_maneuvers.py --kelvin build/ci/tools/kelvin [--jobs 2]
       [--work build/bench/cfd_maneuvers] [--write BENCHMARKS.md]
   the DTC: ... --name cfd_maneuvers_dtc --case data/cases/free_running/dtc_turning.yaml
       --maneuvers turning:35 zigzag:10/10 --swirl on
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
from pimple_vs_openfoam import write_or_print  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
CASE = os.path.join(ROOT, "data/cases/free_running/wigley_turning.yaml")
MANEUVERS = ["turning:35", "zigzag:10/10", "zigzag:20/20"]
METRICS = {"turning": ["advance_over_L", "tactical_diameter_over_L", "steady_diameter_over_L", "steady_rate",
                       "time_to_90"],
           "zigzag": ["first_overshoot", "second_overshoot", "first_overshoot_time", "second_overshoot_time"]}


def run_name(maneuver, side, swirl):
    return f"{maneuver.replace(':', '_').replace('/', '_')}_{side}_{'swirl' if swirl else 'noswirl'}"


def case_motion(case):
    """(ship file, approach speed) of a free-running case."""
    with open(case) as f:
        c = yaml.safe_load(f)
    ship = os.path.normpath(os.path.join(os.path.dirname(case), c["motion"]["ship"]))
    return ship, float(c["motion"]["initial"]["u"])


def case_text(case, maneuver, side, swirl):
    """The case with absolute paths, the maneuver and the propeller's swirl."""
    with open(case) as f:
        text = f.read()
    case_dir = os.path.dirname(case)
    absolute = lambda m: f"{m.group(1)}{os.path.normpath(os.path.join(case_dir, m.group(2)))}"  # noqa: E731
    text = re.sub(r"(poly_mesh: )([^\s}]+)", absolute, text)
    text = re.sub(r"(\n  ship: )(\S+)", absolute, text)
    kind = re.search(r'kind: "(turning|zigzag)[^"]*"', text)
    if not kind or "\npropeller:\n" not in text:
        sys.exit(f"{case}: expected a 'maneuver: {{kind: \"...\"}}' and a 'propeller:' block to edit")
    new = text.replace(kind.group(0), f'kind: "{maneuver}:{side}"', 1)
    if not swirl:
        new = new.replace("\npropeller:\n", "\npropeller:\n  swirl: false\n", 1)
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


def cpu_file(work, name):
    return os.path.join(work, name, "cpu_seconds")


def run_all(kelvin, work, runs, jobs, reuse):
    """Runs the cases `jobs` at a time; returns CPU seconds per run (children's rusage, kept in
    <run>/cpu_seconds). With `reuse`, a run with its maneuver.h5 and cpu_seconds is not run again."""
    pending, running, cpu = [], {}, {}
    for name, text in runs:
        done = os.path.exists(os.path.join(work, name, "out", "maneuver.h5")) and os.path.exists(cpu_file(work, name))
        if reuse and done:
            with open(cpu_file(work, name)) as f:
                cpu[name] = float(f.read())
            print(f"{name}: reused ({cpu[name]:.1f} CPU s when it ran)", file=sys.stderr)
        else:
            pending.append((name, text))
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
        with open(cpu_file(work, name), "w") as f:
            f.write(f"{cpu[name]:.3f}\n")
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


def simulator_cpu(kelvin, work, ship, speed, maneuvers, derivatives):
    """CPU seconds of kelvin simulate flying all the maneuvers at the approach speed (one process)."""
    args = [kelvin, "simulate", ship, "--speed", str(speed), "-o", os.path.join(work, "simulate")]
    if derivatives:
        args += ["--derivatives", derivatives]
    for m in maneuvers:
        for side in ("stbd", "port"):
            args += ["-m", f"{m}:{side}"]
    t0 = os.times()
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
    t1 = os.times()
    return (t1.children_user - t0.children_user) + (t1.children_system - t0.children_system), 2 * len(maneuvers)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kelvin", required=True, help="path to the kelvin program")
    ap.add_argument("--case", default=CASE, help="free-running case (default the Wigley's)")
    ap.add_argument("--name", default="cfd_maneuvers", help="section name (default cfd_maneuvers)")
    ap.add_argument("--maneuvers", nargs="+", default=MANEUVERS, help="maneuvers without the side")
    ap.add_argument("--swirl", choices=["both", "on", "off"], default="both", help="propeller swirl (default both)")
    ap.add_argument("--derivatives", help="derivative set for the simulator's timing (a ship file without a hull)")
    ap.add_argument("--jobs", type=int, default=2, help="runs at a time (default 2)")
    ap.add_argument("--work", help="work directory (default build/bench/<name>)")
    ap.add_argument("--write", help="replace the section in this file (e.g. BENCHMARKS.md)")
    ap.add_argument("--reuse", action="store_true", help="keep runs that finished in an earlier call (their CPU time too)")
    args = ap.parse_args()
    if args.jobs < 1:
        sys.exit(f"--jobs {args.jobs}: expected at least 1")
    for m in args.maneuvers:
        if m.split(":")[0] not in METRICS or m.count(":") != 1:
            sys.exit(f"--maneuvers {m}: expected turning:<deg> or zigzag:<deg>/<deg> (the side is added)")
    case = os.path.abspath(args.case)
    ship, speed = case_motion(case)
    work = args.work or os.path.join(ROOT, "build/bench", args.name)
    swirls = {"both": (False, True), "on": (True,), "off": (False,)}[args.swirl]
    runs = [(run_name(m, side, swirl), case_text(case, m, side, swirl))
            for swirl in swirls for m in args.maneuvers for side in ("stbd", "port")]
    start = time.time()
    cpu = run_all(args.kelvin, work, runs, args.jobs, args.reuse)
    sim_cpu, sim_runs = simulator_cpu(args.kelvin, work, ship, speed, args.maneuvers, args.derivatives)
    rel = lambda p: os.path.relpath(p, ROOT)  # noqa: E731

    out = [f"## {args.name}: IMO maneuvers in free-running CFD (issue #21, acceptances 2, 4 and 5)", "",
           f"`tools/bench/cfd_maneuvers.py --jobs {args.jobs}` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}: "
           f"`{rel(case)}` (the body-force propeller and rudder of `{rel(ship)}`, approach at {speed:g} m/s), "
           "steered by the simulator's maneuver controller. See the case file for the grid and what is assumed. "
           f"{len(runs)} runs, {args.jobs} at a time"
           + (f", {time.time() - start:.0f} s wall." if len(cpu) == 0 or not args.reuse else
              " (finished runs of an earlier call reused with the CPU time they took).")
           + (f" The simulator's timing flies the derivative set `{rel(args.derivatives)}`." if args.derivatives else ""),
           ""]
    for swirl in swirls:
        out += [f"### Propeller swirl {'on' if swirl else 'off'}", "",
                "| maneuver | metric | starboard | port | port / starboard - 1 |", "| --- | --- | ---: | ---: | ---: |"]
        for m in args.maneuvers:
            s, _, _, _ = result(work, run_name(m, "stbd", swirl))
            p, _, _, _ = result(work, run_name(m, "port", swirl))
            for k in METRICS[m.split(":")[0]]:
                rel_diff = p[k] / s[k] - 1 if s[k] != 0 else float("nan")
                out.append(f"| {m} | {k} | {s[k]:.4f} | {p[k]:.4f} | {100 * rel_diff:+.2f}% |")
        out.append("")
    out += ["### Cost", "", "| run | cells | steps | simulated (s) | CPU (s) | CPU-h / Mcell / simulated s |",
            "| --- | ---: | ---: | ---: | ---: | ---: |"]
    total, cells = 0.0, 0
    for name, _ in runs:
        _, t_end, steps, cells = result(work, name)
        total += cpu[name]
        out.append(f"| {name} | {cells} | {steps} | {t_end:.2f} | {cpu[name]:.1f} | "
                   f"{cpu[name] / 3600 / (cells / 1e6) / t_end:.4f} |")
    per_sim = sim_cpu / sim_runs
    out += ["", f"`kelvin simulate` (CVODE, MMG) flew the {sim_runs} maneuvers in {sim_cpu:.2f} "
            f"CPU s in one process, start-up included ({per_sim:.3f} s each); the {len(runs)} CFD runs took "
            f"{total:.0f} CPU s ({total / len(runs):.1f} s each): the CFD costs about {total / len(runs) / per_sim:.0f} "
            f"times the surrogate per maneuver on this {cells}-cell grid, and the ratio grows with the cells. No "
            "published CPU cost of a resolved-propeller free-running CFD maneuver was found in the search corpora, so "
            "none is compared.", ""]
    write_or_print(args.write, args.name, "\n".join(out))


if __name__ == "__main__":
    main()
