#!/usr/bin/env python3
"""Long fuzz campaign of kelvin's readers: runs every libFuzzer target of a
fuzz build (tests/fuzz, `cmake --preset fuzz`) one after the other, each up to
its execution count or its share of the time budget, and writes the
BENCHMARKS.md section `fuzz` (executions, exec/s, crashes, leaks, UB reports).

    cmake --preset fuzz && cmake --build --preset fuzz
    nice -n 19 tools/bench/fuzz_campaign.py --build build/fuzz --skip-reached --fastest-first --write BENCHMARKS.md

The acceptance counts (issue 24): 10 million executions for the hull, polyMesh
and YAML readers, 1 million for the others. Each target's count must be
reached by ONE libFuzzer invocation; the script never adds runs together.

The campaign may span several sessions. Every finished target run is stored
in results/fuzz/campaign.json of this repository (written atomically, committed
with the BENCHMARKS section it renders, so a build directory lost between
sessions loses no measurement) with its
date, the commit of HEAD and of the target's reader sources, and a digest of
those sources; the BENCHMARKS section is rendered from every stored result,
so each row may come from a different session. The reader sources of a target
are what its fuzz binary is compiled from: the sources and headers of its
objects (from ninja's dependency log of the fuzz build), inside this
repository; a target whose binary is older than one of them is not run. --skip-reached runs only the targets without a stored run that
reached its count on the reader sources as they are now (same digest).

A new run replaces the stored one of its target, except that a run that did
not reach its count never replaces one that did on the same reader sources.

--budget (seconds of wall time) runs the targets fastest first (rates from a
short probe) with an equal share each of the core time left; --until HH:MM
(UTC, the next such time, past midnight too) stops every run at that time (a
stopped run is stored as not reached) and starts no target that its stored
rate (or, with --probe, the rate of a short probe now) says cannot reach its
count by then.
--parallel N runs N targets at a time (one core each; libFuzzer's own -jobs
would split one target's executions over processes that report separately).

A target with tests/fuzz/libhdf5_defects/<target> (its library crashes on
corrupt input within seconds) runs in libFuzzer's fork mode, one invocation
that goes on past crashes; each crash input is replayed, and one whose first
frame outside the sanitizer and libc is in libhdf5 is counted apart from
kelvin's crashes.
"""

import argparse
import datetime
import hashlib
import json
import os
import re
import subprocess
import sys
import tempfile
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pimple_vs_openfoam import write_or_print  # noqa: E402

NAME = "fuzz"
BIG = ("stl", "obj", "polymesh", "yaml")  # 10 million executions; the others 1 million
PROBE_SECONDS = 5
# One input running this long is reported as a hang. Under nice 19 on a busy 2-core machine a run can be
# descheduled for over 10 s (two inputs of December 4, 2026 "timed out" at 14 s and replay in 6 ms).
TIMEOUT_SECONDS = 60
# ASan's quarantine of freed memory at 16 MB instead of 256: with the default the YAML targets' resident size
# climbed to about 1 GB within minutes and their rate then fell tenfold (tests/fuzz/README.md).
ASAN_OPTIONS = "allocator_may_return_null=1:quarantine_size_mb=16"
SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def required_runs(target):
    return 10_000_000 if any(k in target for k in BIG) else 1_000_000


def git(*args):
    return subprocess.run(["git", "-C", SOURCE, *args], capture_output=True, text=True).stdout.strip()


# ---------------------------------------------------------------------------
# The reader sources of a target.

def ninja_query_inputs(build, node):
    """Explicit and implicit inputs of a ninja node (not the order-only ones)."""
    out = subprocess.run(["ninja", "-C", build, "-t", "query", node], capture_output=True, text=True).stdout
    inputs, section = [], None
    for line in out.splitlines():
        s = line.strip()
        if s.startswith("input:"):
            section = "input"
            continue
        if s.endswith(":") and not s.startswith("|"):  # outputs:, validations:
            section = None
            continue
        if section == "input" and s and not s.startswith("||"):
            inputs.append(s[2:] if s.startswith("| ") else s)
    return inputs


def linked_sources(binary):
    """The source files of the compile units linked into `binary` (from its debug information)."""
    out = subprocess.run(["llvm-dwarfdump-14", "--debug-info", "--recurse-depth=0", binary],
                         capture_output=True, text=True).stdout
    names, in_cu = set(), False
    for line in out.splitlines():
        if "DW_TAG_compile_unit" in line:
            in_cu = True
        elif in_cu and "DW_AT_name" in line:
            m = re.search(r'\("(.*)"\)', line)
            if m:
                names.add(os.path.realpath(m.group(1)))
            in_cu = False
    return names


def reader_files(build, target):
    """The repository files the target's binary is compiled from (sources and headers of the objects linked
    into it, not those of the rest of a static library), sorted."""
    exe = f"tests/fuzz/{target}_fuzzer"
    objects, pending, seen = [], [exe], set()
    while pending:
        node = pending.pop()
        if node in seen:
            continue
        seen.add(node)
        for i in ninja_query_inputs(build, node):
            if i.endswith(".o"):
                objects.append(i)
            elif i.endswith(".a") and not os.path.isabs(i):
                pending.append(i)
    linked = linked_sources(os.path.join(build, exe))
    files = set()
    if objects:
        out = subprocess.run(["ninja", "-C", build, "-t", "deps", *objects], capture_output=True, text=True).stdout
        build_abs = os.path.realpath(build)
        blocks, deps = [], None
        for line in out.splitlines():
            if line.startswith("    "):
                if deps is not None:
                    deps.append(os.path.realpath(os.path.join(build, line.strip())))
            elif line.strip():
                deps = []
                blocks.append(deps)
        for deps in blocks:
            # An object of a static library is linked only when something refers to it; without debug
            # information (no compile units found) every object counts.
            if linked and not any(d in linked for d in deps if d.endswith((".cc", ".cpp", ".c"))):
                continue
            for p in deps:
                if p.startswith(SOURCE + os.sep) and not p.startswith(build_abs + os.sep):
                    files.add(os.path.relpath(p, SOURCE))
    return sorted(files)


def reader_state(build, target):
    """Digest, last commit and local edits of the target's reader sources."""
    files = reader_files(build, target)
    h = hashlib.sha256()
    for f in files:
        h.update(f.encode() + b"\0")
        try:
            with open(os.path.join(SOURCE, f), "rb") as fh:
                h.update(hashlib.sha256(fh.read()).digest())
        except OSError:
            h.update(b"missing")
    commit = git("log", "-1", "--format=%h", "--", *files) if files else ""
    dirty = bool(git("status", "--porcelain", "--", *files)) if files else False
    return {"reader_digest": h.hexdigest()[:16] if files else "", "reader_commit": commit,
            "reader_dirty": dirty, "reader_files": len(files)}


def stale_sources(build, target):
    """Reader sources edited after the target's binary was linked (the digest would not be what it runs)."""
    binary = os.path.join(build, "tests/fuzz", target + "_fuzzer")
    built = os.path.getmtime(binary)
    return [f for f in reader_files(build, target)
            if os.path.exists(os.path.join(SOURCE, f)) and os.path.getmtime(os.path.join(SOURCE, f)) > built]


# ---------------------------------------------------------------------------
# Stored results.

def load_file(path):
    """results.json: {"targets": {target: its stored run}, "notes": {target: what its row needs said}}."""
    if not os.path.exists(path):
        return {"targets": {}, "notes": {}}
    with open(path) as f:
        data = json.load(f)
    data.setdefault("targets", {})
    data.setdefault("notes", {})
    return data


def load_results(path):
    return load_file(path)["targets"]


def save_results(path, results=None, notes=None):
    """Writes results.json atomically (a temporary file in the same directory, then a rename); what is not
    given is kept as stored."""
    data = load_file(path)
    if results is not None:
        data["targets"] = results
    if notes is not None:
        data["notes"] = notes
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=".results.", dir=os.path.dirname(os.path.abspath(path)))
    try:
        with os.fdopen(fd, "w") as f:
            json.dump(data, f, indent=1, sort_keys=True)
            f.write("\n")
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def reached(r):
    return r["runs"] >= r["required"]


def store(path, lock, r):
    """Stores a finished run, unless it did not reach its count and the stored one did on the same sources."""
    with lock:
        results = load_results(path)
        old = results.get(r["target"])
        if old and reached(old) and not reached(r) and old.get("reader_digest") == r["reader_digest"]:
            print(f"{r['target']}: not stored (the stored run of {old['date']} reached its count)", flush=True)
            return
        results[r["target"]] = r
        save_results(path, results)


# ---------------------------------------------------------------------------
# Running.

def library_defects_target(target):
    """A target whose library (Debian's libhdf5) crashes on corrupt input (tests/fuzz/README.md): it runs in
    libFuzzer's fork mode, which goes on past a crash, and each crash is replayed to say where it happened."""
    return os.path.isdir(os.path.join(SOURCE, "tests/fuzz/libhdf5_defects", target))


def in_libhdf5(r):
    """' (+N in libhdf5)' for a run with crashes inside libhdf5, else ''."""
    return f" (+{r['library_defects']} in libhdf5)" if r.get("library_defects") else ""


def replay(binary, artifact, env):
    """What an artifact's replay reports: (kind, site), kind 'leak', 'ub' or 'crash' (an out-of-memory
    included), or 'none' when the input runs clean alone; site 'libhdf5' when the first frame outside libFuzzer, the sanitizer, its allocator and
    interceptors and libc is in libhdf5, else 'kelvin'."""
    # The malloc limit of the campaign, but a higher RSS limit: an input whose RSS creeps up to the limit before
    # its one huge malloc is then reported at that malloc, with its stack, not by the RSS thread without one. The
    # time-out makes libFuzzer print the stack of a hang.
    try:
        p = subprocess.run([binary, "-malloc_limit_mb=2048", "-rss_limit_mb=8192", f"-timeout={TIMEOUT_SECONDS}", artifact],
                           env=env, capture_output=True, text=True, errors="replace", timeout=2 * TIMEOUT_SECONDS)
    except subprocess.TimeoutExpired:
        return "crash", "kelvin"
    if p.returncode == 0:
        return "none", "not reproduced"  # it crashed only inside the fork-mode run
    out = p.stderr
    kind = "leak" if "ERROR: LeakSanitizer" in out else "ub" if "runtime error:" in out else "crash"
    for line in out.splitlines():
        m = re.match(r"\s+#\d+ 0x[0-9a-f]+ (?:in (\S+) )?(.*)", line)
        if not m:
            continue
        func, where = m.group(1) or "", m.group(2)
        if (func.startswith(("__interceptor_", "__sanitizer", "__asan", "fuzzer::"))
                or func in ("malloc", "calloc", "realloc", "free", "operator", "main") or "libc.so" in where
                or "sysdeps" in where):
            continue
        return kind, "libhdf5" if "libhdf5" in where else "kelvin"
    return kind, "kelvin"


def fuzz(build, target, runs, seconds, work):
    """Runs one target; returns its statistics and what went wrong."""
    fuzz_dir = os.path.join(build, "fuzz")
    corpus = os.path.join(work, "corpus", target)
    artifacts = os.path.join(work, "artifacts", target)
    os.makedirs(corpus, exist_ok=True)
    os.makedirs(artifacts, exist_ok=True)
    before = set(os.listdir(artifacts))
    env = dict(os.environ, UBSAN_OPTIONS="print_stacktrace=1", ASAN_OPTIONS=ASAN_OPTIONS,
               LSAN_OPTIONS="suppressions=" + os.path.join(SOURCE, "tests/fuzz/lsan.supp"))
    binary = os.path.join(build, "tests/fuzz", target + "_fuzzer")
    fork = library_defects_target(target)
    cmd = [binary, f"-runs={runs}", f"-max_total_time={int(seconds)}",
           f"-timeout={TIMEOUT_SECONDS}", "-rss_limit_mb=2048", "-print_funcs=0", f"-artifact_prefix={artifacts}/", "-print_final_stats=1",
           *(["-fork=1", "-ignore_crashes=1", "-ignore_ooms=1", "-ignore_timeouts=1"] if fork else []),
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

    new = sorted(set(os.listdir(artifacts)) - before)  # this run's
    r = {
        "target": target, "runs": stat("number_of_executed_units"), "required": required_runs(target),
        "exec_s": stat("average_exec_per_sec"), "seconds": wall, "rss_mb": stat("peak_rss_mb"), "corpus": len(os.listdir(corpus)),
        "leaks": len(re.findall(r"ERROR: LeakSanitizer", log)),
        "ub": len(re.findall(r"runtime error:", log)),
        # A run stopped from outside (SIGINT, SIGTERM) exits non-zero after "run interrupted": not a crash.
        "crashes": int(p.returncode != 0 and not re.search(r"ERROR: LeakSanitizer|runtime error:|libFuzzer: run "
                                                           r"interrupted", log)),
        "interrupted": bool(re.search(r"libFuzzer: run interrupted", log)),
        "artifacts": new,
        "timeout": bool(re.search(r"ERROR: libFuzzer: timeout", log)),
    }
    if fork:
        # Fork mode prints its progress as "#N: cov: ..." and each crash as one line: count the executions
        # from the last progress line and sort the crashes by replaying their inputs.
        progress = re.findall(r"^#(\d+): cov:", log, re.M)
        r["runs"] = int(progress[-1]) if progress else 0
        r["exec_s"] = int(r["runs"] / wall) if wall > 0 else 0
        r.update(crashes=0, leaks=0, ub=0, library_defects=0, fork=True)
        for a in new:
            if a.startswith(("timeout-", "slow-unit-")):
                r["timeout"] = r["timeout"] or a.startswith("timeout-")
                continue
            kind, site = replay(binary, os.path.join(artifacts, a), env)
            if kind == "none":
                r["not_reproduced"] = r.get("not_reproduced", 0) + 1
                continue
            key = "library_defects" if site == "libhdf5" else {"leak": "leaks", "ub": "ub", "crash": "crashes"}[kind]
            r[key] += 1
        # Its exit status is that of the last failed job; with no progress line the parent itself failed.
        r["crashes"] += int(p.returncode != 0 and not progress)
    return r


def plan(build, targets, budget, work):
    """Targets fastest first (by their time to reach the count), from a short probe."""
    rates = {}
    start = time.monotonic()
    for t in targets:
        r = fuzz(build, t, 10 ** 9, PROBE_SECONDS, work)
        rates[t] = max(r["exec_s"], 1)
        print(f"probe {t}: {rates[t]} exec/s", flush=True)
    return sorted(targets, key=lambda t: required_runs(t) / rates[t]), budget - (time.monotonic() - start)


def fastest_first(build, targets, stored, work):
    """Targets by their time to reach the count: the stored rate where there is one, else a short probe."""
    rates = {}
    for t in targets:
        if t in stored and stored[t].get("exec_s"):
            rates[t] = stored[t]["exec_s"]
        else:
            rates[t] = max(fuzz(build, t, 10 ** 9, PROBE_SECONDS, work)["exec_s"], 1)
            print(f"probe {t}: {rates[t]} exec/s", flush=True)
    return sorted(targets, key=lambda t: required_runs(t) / rates[t]), rates



def run_campaign(build, order, budget, parallel, work, results_path, until=None, rates=None):
    """Runs the targets in order, `parallel` at a time; with a budget (s of wall time), each target starting
    gets an equal share of the core time not yet promised to the targets running. With `until` (a UTC
    datetime) no run goes past it, and a target whose rate says it cannot reach its count by then is skipped."""
    deadline = time.monotonic() + budget
    lock, store_lock = threading.Lock(), threading.Lock()
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
                if until:
                    to_go = (until - datetime.datetime.now(datetime.timezone.utc)).total_seconds()
                    need = required_runs(t) / rates[t] if rates and rates.get(t) else 0
                    if to_go < 1 or need > to_go:
                        print(f"{t}: skipped, {need:.0f} s needed at {rates.get(t) if rates else '?'} exec/s, "
                              f"{max(to_go, 0):.0f} s left before {until:%H:%M} UTC", flush=True)
                        continue
                    seconds = min(seconds, to_go)
                promised[t] = time.monotonic() + seconds
                print(f"{t}: started at {datetime.datetime.now(datetime.timezone.utc):%H:%M:%S} UTC", flush=True)
            stale = stale_sources(build, t)
            if stale:
                print(f"{t}: skipped, its binary is older than {', '.join(stale[:3])}"
                      f"{' ...' if len(stale) > 3 else ''}: rebuild the fuzz build", flush=True)
                with lock:
                    promised.pop(t)
                continue
            state = reader_state(build, t)
            r = fuzz(build, t, required_runs(t), seconds, work)
            date = datetime.datetime.now(datetime.timezone.utc)
            r.update(state, date=f"{date:%Y-%m-%d %H:%M} UTC", commit=git("rev-parse", "--short", "HEAD"),
                     head_dirty=bool(git("status", "--porcelain", "--untracked-files=no")))
            store(results_path, store_lock, r)
            with lock:
                promised.pop(t)
                results.append(r)
                print(f"{t}: {r['runs']:,} executions, {r['exec_s']:,} exec/s, {r['crashes']} crashes"
                      f"{in_libhdf5(r)}"
                      f"{' (a timeout: replay the artifact to tell a hang from a stall)' if r.get('timeout') else ''}, "
                      f"{r['leaks']} leaks, {r['ub']} UB", flush=True)

    threads = [threading.Thread(target=worker) for _ in range(parallel)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    return results


# ---------------------------------------------------------------------------
# The BENCHMARKS section.

def section(stored, targets, build, current, notes):
    """The section from every stored result; `current` maps each target to its reader state now; `notes`
    (target: text) are said under the table."""
    rows = [stored[t] for t in targets if t in stored] + [stored[t] for t in sorted(stored) if t not in targets]
    total = sum(r["runs"] for r in rows)
    met = [r for r in rows if reached(r)]
    missing = [t for t in targets if t not in stored]
    dates = sorted(r["date"][:10] for r in rows)
    lines = [
        "## fuzz: the readers under libFuzzer (issue 24)\n",
        f"One campaign run in several sessions ({dates[0]} to {dates[-1]}) with "
        f"`tools/bench/fuzz_campaign.py --build {build}` (results stored in "
        "`results/fuzz/campaign.json`, this section rendered from them): each row is ONE libFuzzer "
        "invocation of its target, started from the corpus the earlier sessions left, not a sum of runs; rows "
        "of different dates come from separate runs of the campaign on the commit shown (the last commit of "
        "the target's reader sources, * when they had local edits at the run). clang 14, -O1, "
        "AddressSanitizer + UBSan (every report aborts), one target at a time under `nice -n 19` on the shared "
        "2-core machine. The acceptance count is 10 million executions for the hull, polyMesh and YAML "
        "readers, 1 million for the others. \"Changed since\": the reader sources (the sources and headers "
        "its fuzz binary is compiled from) differ from those of the run. Every input that crashed a target during "
        "development is replayed by ctest (`fuzz_<target>_regressions`, from tests/fuzz/regressions/).\n",
        "| target | executions | count | reached | exec/s | time (s) | corpus | crashes | leaks | UB | date | commit | changed since |",
        "|---|---:|---:|:---:|---:|---:|---:|---:|---:|---:|---|---|:---:|",
    ]
    for r in rows:
        changed = current.get(r["target"], {}).get("reader_digest") != r.get("reader_digest")
        commit = (r.get("reader_commit") or r.get("commit", "?")) + ("*" if r.get("reader_dirty") else "")
        lines.append(f"| {r['target']} | {r['runs']:,} | {r['required']:,} | {'yes' if reached(r) else 'no'}"
                     f" | {r['exec_s']:,} | {r['seconds']:.0f} | {r['corpus']} | {r['crashes']}"
                     f"{in_libhdf5(r)}"
                     f" | {r['leaks']} | {r['ub']}"
                     f" | {r.get('date', '?')} | {commit} | {'yes' if changed else 'no'} |")
    lines.append("")
    lines.append(f"{total:,} executions in these rows; {len(met)} of {len(targets)} targets reached their count; "
                 f"{sum(r['crashes'] for r in rows)} crashes, {sum(r['leaks'] for r in rows)} leaks, "
                 f"{sum(r['ub'] for r in rows)} UB reports.")
    forked = [r for r in rows if r.get("fork")]
    if forked:
        lines.append("Run in libFuzzer's fork mode, which goes on past a crash (their library crashes on corrupt "
                     "files within seconds; tests/fuzz/README.md): " + ", ".join(r["target"] for r in forked) +
                     "; each crash input was replayed, and \"+N in libhdf5\" counts those whose crashing frame is "
                     "inside Debian's libhdf5, not in kelvin.")
    if missing:
        lines.append(f"Not run yet: {', '.join(missing)}.")
    todo = [r for r in rows if not reached(r) and r["exec_s"]]
    if todo:
        lines.append("Still to reach their count, with the core time one run needs at the rate of its row: " +
                     "; ".join(f"{r['target']} {required_runs(r['target']) / r['exec_s'] / 3600:.1f} h" for r in todo) + ".")
    for r in rows:
        if r["artifacts"] or notes.get(r["target"]):
            found = r["artifacts"] if len(r["artifacts"]) <= 10 else [
                f"{len(r['artifacts'])} artifact files ({r['artifacts'][0]} ... {r['artifacts'][-1]})"]
            lines.append(f"- {r['target']}: " + "; ".join(filter(None, [", ".join(found), notes.get(r["target"])])))
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build/fuzz", help="the fuzz build directory")
    ap.add_argument("--targets", nargs="*", help="default: every target of the build (fuzz/targets.txt)")
    ap.add_argument("--budget", type=float, default=0, help="total seconds; 0: each target runs to its count")
    ap.add_argument("--parallel", type=int, default=1, help="targets at a time (one core each)")
    ap.add_argument("--work", help="corpora, crashes and logs (default <build>/fuzz/campaign)")
    ap.add_argument("--results", help="the stored results (default results/fuzz/campaign.json in the repository)")
    ap.add_argument("--skip-reached", action="store_true",
                    help="run only targets without a stored run that reached its count on the current reader sources")
    ap.add_argument("--fastest-first", action="store_true",
                    help="order by time to reach the count (stored rates, else a short probe)")
    ap.add_argument("--until", help="HH:MM UTC, the next one: no run goes past it (stopped runs do not reach their count)")
    ap.add_argument("--probe", action="store_true",
                    help="rate the targets by a short probe now, not by their stored runs (a stored rate measured "
                         "beside other targets understates one running alone)")
    ap.add_argument("--note", action="append", default=[], metavar="TARGET=TEXT",
                    help="store a note said under the table for TARGET (empty TEXT removes it)")
    ap.add_argument("--render-only", action="store_true", help="run nothing; write the section from the stored results")
    ap.add_argument("--write", help="BENCHMARKS.md to update (default: print the section)")
    args = ap.parse_args()
    if args.parallel < 1:
        ap.error(f"--parallel {args.parallel}: expected at least 1")
    work = args.work or os.path.join(args.build, "fuzz", "campaign")
    results_path = args.results or os.path.join(SOURCE, "results", "fuzz", "campaign.json")
    all_targets = open(os.path.join(args.build, "fuzz", "targets.txt")).read().split()
    targets = args.targets or all_targets
    until = None
    if args.until:
        if not re.fullmatch(r"\d\d?:\d\d", args.until):
            ap.error(f"--until {args.until}: expected HH:MM")
        h, m = map(int, args.until.split(":"))
        now = datetime.datetime.now(datetime.timezone.utc)
        until = now.replace(hour=h, minute=m, second=0, microsecond=0)
        if until <= now:  # the next HH:MM: a campaign started before midnight runs into the next day
            until += datetime.timedelta(days=1)
    if args.note:
        notes = load_file(results_path)["notes"]
        for n in args.note:
            t, sep, text = n.partition("=")
            if not sep:
                ap.error(f"--note {n}: expected TARGET=TEXT")
            if text:
                notes[t] = text
            else:
                notes.pop(t, None)
        save_results(results_path, notes=notes)
    stored = load_results(results_path)
    current = {t: reader_state(args.build, t) for t in set(all_targets) | set(targets) | set(stored)}
    if not args.render_only:
        order = list(targets)
        if args.skip_reached:
            done = [t for t in order if t in stored and reached(stored[t])
                    and stored[t].get("reader_digest") == current[t]["reader_digest"]]
            for t in done:
                print(f"{t}: skipped, reached {stored[t]['runs']:,} on {stored[t]['date']} on these reader sources",
                      flush=True)
            order = [t for t in order if t not in done]
        budget, rates = args.budget, None
        if order and budget:
            order, budget = plan(args.build, order, budget, work)
        elif order and (args.fastest_first or args.probe):
            order, rates = fastest_first(args.build, order, {} if args.probe else stored, work)
        elif until:  # the stored rates tell which targets can still reach their count; the others start anyway
            rates = {t: stored[t]["exec_s"] for t in order if t in stored and stored[t].get("exec_s")}
        print("order: " + " ".join(order), flush=True)
        run_campaign(args.build, order, budget, args.parallel, work, results_path, until, rates)
        stored = load_results(results_path)
        current = {t: reader_state(args.build, t) for t in set(all_targets) | set(stored)}
    if not stored:
        sys.exit(f"no results stored in {results_path}")
    write_or_print(args.write, NAME, section(stored, all_targets, args.build, current, load_file(results_path)["notes"]))


if __name__ == "__main__":
    main()
