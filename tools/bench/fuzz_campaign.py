#!/usr/bin/env python3
"""Long fuzz campaign of kelvin's readers: runs every libFuzzer target of a
fuzz build (tests/fuzz, `cmake --preset fuzz`) one after the other, each up to
its execution count or its share of the time budget, and writes the
BENCHMARKS.md section `fuzz` (executions, exec/s, crashes, leaks, UB reports).

    cmake --preset fuzz && cmake --build --preset fuzz
    nice -n 10 tools/bench/fuzz_campaign.py --build build/fuzz --budget 6000 --parallel 2 --write BENCHMARKS.md

The acceptance counts (issue 24): 10 million executions for the hull, polyMesh
and YAML readers, 1 million for the others. With --budget the targets run
fastest first (rates from a short probe), so that as many as possible reach
their count; each gets an equal share of the core time left. --parallel N
runs N targets at a time (one core each; libFuzzer's own -jobs would split
one target's executions over processes that report separately).
"""

import argparse
import datetime
import os
import re
import subprocess
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pimple_vs_openfoam import write_or_print  # noqa: E402

NAME = "fuzz"
BIG = ("stl", "obj", "polymesh", "yaml")  # 10 million executions; the others 1 million
PROBE_SECONDS = 5


def required_runs(target):
    return 10_000_000 if any(k in target for k in BIG) else 1_000_000


def fuzz(build, target, runs, seconds, work):
    """Runs one target; returns its statistics and what went wrong."""
    fuzz_dir = os.path.join(build, "fuzz")
    corpus = os.path.join(work, "corpus", target)
    artifacts = os.path.join(work, "artifacts", target)
    os.makedirs(corpus, exist_ok=True)
    os.makedirs(artifacts, exist_ok=True)
    source = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    env = dict(os.environ, UBSAN_OPTIONS="print_stacktrace=1", ASAN_OPTIONS="allocator_may_return_null=1",
               LSAN_OPTIONS="suppressions=" + os.path.join(source, "tests/fuzz/lsan.supp"))
    cmd = [os.path.join(build, "tests/fuzz", target + "_fuzzer"), f"-runs={runs}", f"-max_total_time={int(seconds)}",
           "-timeout=10", "-rss_limit_mb=2048", "-print_funcs=0", f"-artifact_prefix={artifacts}/", "-print_final_stats=1",
           corpus, os.path.join(fuzz_dir, "seeds", target)]
    start = time.monotonic()
    p = subprocess.run(cmd, env=env, capture_output=True, text=True, errors="replace")
    wall = time.monotonic() - start
    log = p.stderr
    with open(os.path.join(work, target + ".log"), "w") as f:
        f.write(log)

    def stat(key):
        m = re.search(rf"stat::{key}:\s*(\d+)", log)
        return int(m.group(1)) if m else 0

    return {
        "target": target, "runs": stat("number_of_executed_units"), "required": required_runs(target),
        "exec_s": stat("average_exec_per_sec"), "seconds": wall, "rss_mb": stat("peak_rss_mb"), "corpus": len(os.listdir(corpus)),
        "leaks": len(re.findall(r"ERROR: LeakSanitizer", log)),
        "ub": len(re.findall(r"runtime error:", log)),
        "crashes": int(p.returncode != 0 and not re.search(r"ERROR: LeakSanitizer|runtime error:", log)),
        "artifacts": sorted(os.listdir(artifacts)),
    }


def plan(build, targets, budget, work):
    """Targets fastest first (by their time to reach the count), from a short probe."""
    rates = {}
    start = time.monotonic()
    for t in targets:
        r = fuzz(build, t, 10 ** 9, PROBE_SECONDS, work)
        rates[t] = max(r["exec_s"], 1)
        print(f"probe {t}: {rates[t]} exec/s", flush=True)
    return sorted(targets, key=lambda t: required_runs(t) / rates[t]), budget - (time.monotonic() - start)


def run_campaign(build, order, budget, parallel, work):
    """Runs the targets in order, `parallel` at a time; with a budget (s of wall time), each target starting
    gets an equal share of the core time not yet promised to the targets running."""
    deadline = time.monotonic() + budget
    lock = threading.Lock()
    pending, promised, results = list(order), {}, []

    def worker():
        while True:
            with lock:
                if not pending:
                    return
                t = pending.pop(0)
                seconds = 10 ** 7
                if budget:
                    now = time.monotonic()
                    left = parallel * (deadline - now) - sum(max(0.0, end - now) for end in promised.values())
                    seconds = max(left / (len(pending) + 1), 1.0)
                promised[t] = time.monotonic() + seconds
            r = fuzz(build, t, required_runs(t), seconds, work)
            with lock:
                promised.pop(t)
                results.append(r)
                print(f"{t}: {r['runs']:,} executions, {r['exec_s']:,} exec/s, {r['crashes']} crashes, "
                      f"{r['leaks']} leaks, {r['ub']} UB", flush=True)

    threads = [threading.Thread(target=worker) for _ in range(parallel)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    return results


def section(results, build, budget, parallel):
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    total = sum(r["runs"] for r in results)
    met = sum(r["runs"] >= r["required"] for r in results)
    lines = [
        "## fuzz: the readers under libFuzzer (issue 24)\n",
        f"`tools/bench/fuzz_campaign.py --build {build}" + (f" --budget {budget}" if budget else "") +
        f" --parallel {parallel}` on {datetime.date.today()} at commit {commit}: clang 14, -O1, AddressSanitizer + "
        f"UBSan (every report aborts), {parallel} target(s) at a time, one core each, on the shared 2-core machine, "
        "from the seed corpora of tests/fuzz/seeds. The acceptance count is 10 million executions for the "
        "hull, polyMesh and YAML readers, 1 million for the others; with a time budget the fastest targets "
        "run first.\n",
        "| target | executions | count | reached | exec/s | time (s) | corpus | crashes | leaks | UB |",
        "|---|---:|---:|:---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in results:
        lines.append(f"| {r['target']} | {r['runs']:,} | {r['required']:,} | {'yes' if r['runs'] >= r['required'] else 'no'}"
                     f" | {r['exec_s']:,} | {r['seconds']:.0f} | {r['corpus']} | {r['crashes']} | {r['leaks']} | {r['ub']} |")
    lines.append("")
    lines.append(f"{total:,} executions in all; {met} of {len(results)} targets reached their count; "
                 f"{sum(r['crashes'] for r in results)} crashes, {sum(r['leaks'] for r in results)} leaks, "
                 f"{sum(r['ub'] for r in results)} UB reports.")
    for r in results:
        if r["artifacts"]:
            lines.append(f"- {r['target']}: {', '.join(r['artifacts'])}")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build/fuzz", help="the fuzz build directory")
    ap.add_argument("--targets", nargs="*", help="default: every target of the build (fuzz/targets.txt)")
    ap.add_argument("--budget", type=float, default=0, help="total seconds; 0: each target runs to its count")
    ap.add_argument("--parallel", type=int, default=1, help="targets at a time (one core each)")
    ap.add_argument("--work", help="corpora, crashes and logs (default <build>/fuzz/campaign)")
    ap.add_argument("--write", help="BENCHMARKS.md to update (default: print the section)")
    args = ap.parse_args()
    if args.parallel < 1:
        ap.error(f"--parallel {args.parallel}: expected at least 1")
    work = args.work or os.path.join(args.build, "fuzz", "campaign")
    targets = args.targets or open(os.path.join(args.build, "fuzz", "targets.txt")).read().split()
    budget = args.budget
    order, budget_left = targets, 0
    if budget:
        order, budget_left = plan(args.build, targets, budget, work)
    results = run_campaign(args.build, order, budget_left if budget else 0, args.parallel, work)
    write_or_print(args.write, NAME, section(sorted(results, key=lambda r: targets.index(r["target"])),
                                             args.build, args.budget, args.parallel))


if __name__ == "__main__":
    main()
