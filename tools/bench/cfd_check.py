#!/usr/bin/python3
"""Benchmark: the surrogate check against free-running CFD (issue 21, acceptances 3 and 4).

Runs the chain a user runs, on a CFD captive campaign that spans the
maneuvers and the free-running CFD runs of the same hull:

    kelvin captive CAMPAIGN --jobs N          (resumes; finished runs are kept)
    kelvin identify <campaign h5> -o WORK/derivatives.yaml
    kelvin check WORK/derivatives.yaml --ship SHIP --against REFERENCES -o WORK/check

and tabulates, maneuver by maneuver, the check's goal metrics (advance and
tactical diameter within 5%, overshoot angles within 2 deg) and the steady
turn, with the interaction coefficients the fit gave beside the ship file's.

Usage: tools/bench/cfd_check.py --kelvin build/ci/tools/kelvin --name cfd_check_wigley
           --campaign data/cases/captive_cfd/wigley_turn_campaign.yaml --ship data/ships/wigley.yaml
           --against 'build/bench/cfd_maneuvers/*_swirl/out/maneuver.h5' [--jobs 2] [--write BENCHMARKS.md]
"""
import argparse
import glob
import os
import re
import subprocess
import sys
import time

import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pimple_vs_openfoam import write_or_print  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
GOAL_METRICS = ["advance", "tactical_diameter", "steady_rate", "first_overshoot", "second_overshoot"]
CHECK_FAILED = 3  # kelvin check's exit status when the set does not reproduce its references


def kelvin(args, log):
    env = dict(os.environ, OMPI_MCA_ess_singleton_isolated="1")
    with open(log, "w") as f:
        return subprocess.run(args, env=env, stdout=f, stderr=subprocess.STDOUT).returncode


def campaign_output(campaign):
    """The campaign HDF5 that kelvin captive writes: <cfd.directory>/<campaign.name>.h5."""
    with open(campaign) as f:
        c = yaml.safe_load(f)
    directory = os.path.normpath(os.path.join(os.path.dirname(campaign), c["cfd"]["directory"]))
    return os.path.join(directory, c["campaign"]["name"] + ".h5")


def run_chain(args, work):
    os.makedirs(work, exist_ok=True)
    t0 = time.time()
    if kelvin([args.kelvin, "captive", args.campaign, "--jobs", str(args.jobs), "--no-progress"],
              os.path.join(work, "captive.log")) != 0:
        sys.exit(f"kelvin captive failed; see {work}/captive.log")
    wall = time.time() - t0
    derivatives = os.path.join(work, "derivatives.yaml")
    if kelvin([args.kelvin, "identify", campaign_output(args.campaign), "-o", derivatives],
              os.path.join(work, "identify.log")) != 0:
        sys.exit(f"kelvin identify failed; see {work}/identify.log")
    references = sorted(p for pattern in args.against for p in glob.glob(pattern))
    if not references:
        sys.exit(f"no reference runs match {args.against}")
    status = kelvin([args.kelvin, "check", derivatives, "--ship", args.ship, "--against", *references,
                     "-o", os.path.join(work, "check")], os.path.join(work, "check.log"))
    if status not in (0, CHECK_FAILED):
        sys.exit(f"kelvin check failed (exit {status}); see {work}/check.log")
    return derivatives, references, wall, status == 0


def report_tables(path):
    """{maneuver: {metric: (unit, reference, surrogate, difference, relative, tolerance, verdict)}} from check_report.md."""
    out, maneuver = {}, None
    with open(path) as f:
        for line in f:
            m = re.match(r"## (\S+) against", line)
            if m:
                maneuver = m.group(1)
                out[maneuver] = {}
                continue
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if maneuver and len(cells) == 8 and cells[0] in GOAL_METRICS:
                out[maneuver][cells[0]] = tuple(cells[1:])
    return out


def metric_table(tables):
    rows = ["| maneuver | metric | unit | CFD | surrogate | difference | relative | goal |",
            "| --- | --- | --- | ---: | ---: | ---: | ---: | --- |"]
    for maneuver, metrics in tables.items():
        for name in GOAL_METRICS:
            if name not in metrics:
                continue
            unit, ref, sur, diff, rel, tol, verdict = metrics[name]
            goal = f"{tol}: {verdict.upper() if verdict == 'fail' else verdict}" if tol else ""
            rows.append(f"| {maneuver} | {name} | {unit} | {ref} | {sur} | {diff} | {rel} | {goal} |")
    return "\n".join(rows)


def range_warnings(check_log):
    """kelvin check's WARNING lines: maneuvers beyond the motions the set was identified over."""
    with open(check_log) as f:
        lines = [line.strip() for line in f if line.strip().startswith("WARNING:")]
    if not lines:
        return "Every maneuver stayed within the drift and r' the captive runs span."
    return "Beyond the identified range (kelvin check's warnings):\n\n" + "\n".join(f"- {line}" for line in lines)


def interaction_table(derivatives, ship):
    with open(derivatives) as f:
        found = yaml.safe_load(f).get("interaction") or {}
    with open(ship) as f:
        s = yaml.safe_load(f)
    assumed = {**(s.get("propeller") or {}), **(s.get("rudder") or {})}
    if not found:
        return "The campaign has no runs with propeller and rudder: the ship file's interaction coefficients are used."
    names = list(found)
    rows = ["| | " + " | ".join(names) + " |", "| --- |" + " ---: |" * len(names),
            "| CFD | " + " | ".join(f"{found[n]:.4g}" for n in names) + " |",
            "| ship file | " + " | ".join(f"{assumed[n]:.4g}" if n in assumed else "-" for n in names) + " |"]
    return "\n".join(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kelvin", required=True, help="path to the kelvin program")
    ap.add_argument("--name", required=True, help="section name in BENCHMARKS.md (e.g. cfd_check_wigley)")
    ap.add_argument("--campaign", required=True, help="CFD captive campaign that spans the maneuvers")
    ap.add_argument("--ship", required=True, help="ship file of the surrogate")
    ap.add_argument("--against", required=True, nargs="+", help="free-running CFD maneuver.h5 files (globs)")
    ap.add_argument("--jobs", type=int, default=2, help="captive runs at a time (default 2)")
    ap.add_argument("--work", help="work directory (default build/bench/<name>)")
    ap.add_argument("--write", help="replace the section in this file (e.g. BENCHMARKS.md)")
    args = ap.parse_args()
    work = args.work or os.path.join(ROOT, "build/bench", args.name)
    derivatives, references, wall, passed = run_chain(args, work)
    tables = report_tables(os.path.join(work, "check", "check_report.md"))
    rel = lambda p: os.path.relpath(os.path.abspath(p), ROOT)  # noqa: E731
    section = "\n".join([
        f"## {args.name}: the surrogate against free-running CFD (issue #21)",
        "",
        f"`tools/bench/cfd_check.py` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}: `kelvin captive "
        f"{rel(args.campaign)}` ({wall:.0f} s wall in this call, `--jobs {args.jobs}`; finished runs are reused), "
        f"`kelvin identify`, then `kelvin check` with the ship file `{rel(args.ship)}` against {len(references)} "
        f"free-running CFD runs ({', '.join('`' + rel(p) + '`' for p in references)}), each from its own approach "
        f"state. Result: **{'PASSED' if passed else 'FAILED'}**.",
        "",
        metric_table(tables),
        "",
        range_warnings(os.path.join(work, "check.log")),
        "",
        "Interaction coefficients identified from the campaign's runs with propeller and rudder:",
        "",
        interaction_table(derivatives, args.ship),
    ]) + "\n"
    write_or_print(args.write, args.name, section)


if __name__ == "__main__":
    main()
