#!/usr/bin/env python3
"""Paper estimate of kelvin's strong scaling from 8 to 256 ranks (issue 23,
acceptance 3): measured partitions, modelled communication.

Measured here: the PT-Scotch partitions of a blockMesh cube of N^3 hexahedra
(default N = 128, 2,097,152 cells, the size of the 2.7-2.8M-cell LFS grids),
cut by tools/bench/partition_stats for each rank count: owned cells, ghost
cells and neighbour ranks of the worst part. Taken from BENCHMARKS.md: the
serial cost per cell and step, t_cell (parallel_speedup section). Assumed and
stated: the counts of halo exchanges and global reductions per time step, the
interconnect's latency and bandwidth, and the shape of hypre's coarse AMG
levels. The model per time step on P ranks is

    T(P) = T_compute + T_halo + T_reduce + T_coarse
    T_compute = t_cell * max_owned
    T_halo    = exchanges * max_neighbours * alpha + 8 B * doubles * max_ghosts / beta
    T_reduce  = reductions * alpha * 2 log2(P)
    T_coarse  = hypre's coarse AMG levels: per V-cycle and per setup, the
                latency and volume of each level's exchanges, with the
                neighbour count growing as the ranks' share of a level shrinks

and the speed-up is t_cell * cells / T(P). It is an estimate, not a cluster
measurement.

Usage: tools/bench/scaling_estimate.py --stats build/ci/tools/bench/partition_stats [--cells 128] [--work DIR] [--write BENCHMARKS.md]
"""
import argparse
import dataclasses
import datetime
import json
import math
import os
import subprocess
import sys
import tempfile

NAME = "scaling_estimate"
AFTER = "parallel_speedup"  # a missing section goes after this one
FOAM_BASHRC = "/usr/share/openfoam/etc/bashrc"
FOAM_FILE = "FoamFile {{ version 2.0; format ascii; class dictionary; object {obj}; }}\n"


# ---------------------------------------------------------------- the mesh

def put(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def cube_case(case, n):
    """A case directory that blockMesh turns into an n^3 unit cube (binary polyMesh)."""
    put(f"{case}/system/controlDict", FOAM_FILE.format(obj="controlDict") +
        "application blockMesh; startFrom startTime; startTime 0; stopAt endTime; endTime 1; deltaT 1;\n"
        "writeControl timeStep; writeInterval 1;\n"
        "writeFormat binary; writePrecision 17; writeCompression off;\n")
    put(f"{case}/system/blockMeshDict", FOAM_FILE.format(obj="blockMeshDict") + f"""scale 1;
vertices ((0 0 0) (1 0 0) (1 1 0) (0 1 0) (0 0 1) (1 0 1) (1 1 1) (0 1 1));
blocks (hex (0 1 2 3 4 5 6 7) ({n} {n} {n}) simpleGrading (1 1 1));
boundary (
  lid {{ type wall; faces ((3 7 6 2)); }}
  walls {{ type wall; faces ((0 4 7 3) (1 2 6 5) (0 1 5 4) (0 3 2 1) (4 5 6 7)); }}
);
""")


def cube_poly_mesh(work, n):
    """constant/polyMesh of the n^3 cube under `work`, made by blockMesh unless already there."""
    case = os.path.join(work, f"cube{n}")
    poly_mesh = os.path.join(case, "constant", "polyMesh")
    stamp = os.path.join(case, "cells.txt")
    if os.path.exists(stamp) and open(stamp).read().strip() == str(n ** 3):
        return poly_mesh
    if not os.path.exists(FOAM_BASHRC):
        sys.exit("OpenFOAM is not installed (Debian package 'openfoam'; run tools/setup)")
    cube_case(case, n)
    log = os.path.join(work, f"blockMesh_{n}.log")
    with open(log, "w") as out:
        done = subprocess.run(["bash", "-c", f"source {FOAM_BASHRC} >/dev/null 2>&1 && blockMesh -case {case}"],
                              stdout=out, stderr=subprocess.STDOUT)
    if done.returncode != 0:
        sys.exit(f"blockMesh failed; see {log}")
    put(stamp, f"{n ** 3}\n")
    return poly_mesh


def partitions(stats, poly_mesh, parts):
    """One dict per part count from partition_stats (JSON lines)."""
    cmd = [stats, poly_mesh, "--parts", ",".join(str(p) for p in parts)]
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed:\n{done.stderr[-3000:]}")
    return [json.loads(line) for line in done.stdout.splitlines() if line.startswith("{")]


# ---------------------------------------------------------------- the counts per time step

@dataclasses.dataclass
class Counts:
    """Communication of one time step of the laminar PIMPLE solver (cfd/solver/pimple_solver.cc)."""
    exchanges: float        # fine-level halo exchanges (kelvin's ghost refreshes, hypre's matvecs and fine smoothing)
    doubles: float          # doubles per ghost cell summed over those exchanges
    reductions: float       # global reductions (Allreduce) outside the AMG coarse levels
    vcycles: float          # BoomerAMG V-cycles (one per CG iteration and one per solve)
    setups: float           # BoomerAMG setups


def step_counts(a):
    outer, corr = a.outer, a.correctors
    # kelvin's own ghost refreshes: per outer grad(U) (9 doubles), grad(p) (3), U after the momentum solve (3);
    # per corrector rAU (1), HbyA (3), p (1), grad(p) (3) and the fluxes of the cut faces (~1 per ghost).
    own_x, own_d = outer * 3 + outer * corr * 5, outer * 15 + outer * corr * 9
    # Reductions: one per corrector (pressure reference), and per step Courant (MAXLOC + Bcast),
    # continuity (4 sums/maxima) and the finite check.
    own_r = outer * corr + 7
    # Momentum: 3 component solves per outer by hypre BiCGStab + Jacobi: 2 matvecs and 5 inner
    # products per iteration, one matvec and 2 norms to start each solve.
    m_solves, m_it = outer * 3, a.momentum_iterations
    mom_x, mom_r = 2 * m_it + m_solves, 5 * m_it + 2 * m_solves
    # Pressure: CG (two-norm) + BoomerAMG: per iteration one matvec, 3 inner products and one V-cycle; per
    # solve one more matvec, 3 norms and the V-cycle of the initial residual. The V-cycle's fine level does
    # `amg_level_exchanges` exchanges (l1-Gauss-Seidel down and up, residual, restriction, interpolation).
    p_solves, p_it = outer * corr, a.cg_iterations
    vcycles = p_it + p_solves
    p_x = p_it + p_solves + a.amg_level_exchanges * vcycles
    p_r = 3 * p_it + 3 * p_solves
    exchanges = own_x + mom_x + p_x
    return Counts(exchanges=exchanges, doubles=own_d + mom_x + p_x, reductions=own_r + mom_r + p_r,
                  vcycles=vcycles, setups=a.amg_setups)


# ---------------------------------------------------------------- hypre's coarse levels

def amg_level_sizes(cells, a):
    """Global unknowns per level: the first (aggressive) coarsening by `amg_first_ratio`, then `amg_ratio`
    per level, down to at most `amg_coarsest` unknowns (assumptions, see the prose)."""
    sizes = [float(cells)]
    while sizes[-1] > a.amg_coarsest:
        sizes.append(sizes[-1] / (a.amg_first_ratio if len(sizes) == 1 else a.amg_ratio))
    return sizes


def coarse_level_comm(n_global, ranks, w):
    """(neighbours, ghosts) of the worst rank on a coarse level of n_global unknowns: the ranks holding
    rows, each a cube of side s = (rows per rank)^(1/3) in level units, coupled through stencils of
    half-width w; capped by the ranks that hold rows and by the rows' couplings."""
    active = max(1, min(ranks, math.ceil(n_global)))
    rows = n_global / active
    side = rows ** (1.0 / 3.0)
    reach = 1 + 2 * math.ceil(w / side)
    neighbours = min(active - 1, reach ** 3 - 1, math.ceil(rows) * (2 * w + 1) ** 3)
    ghosts = min(n_global - rows, (side + 2 * w) ** 3 - side ** 3)
    return neighbours, ghosts


def t_coarse(cells, ranks, counts, a):
    """The coarse AMG levels per time step: V-cycles (levels 1.. except the coarsest: exchanges; the
    coarsest: Gaussian elimination on a gathered system, one all-gather) and setups (every level)."""
    if ranks == 1:
        return 0.0
    sizes = amg_level_sizes(cells, a)
    per_cycle = 0.0
    for n in sizes[1:-1]:
        nbr, ghosts = coarse_level_comm(n, ranks, a.amg_stencil)
        per_cycle += a.amg_level_exchanges * (nbr * a.alpha + 8.0 * ghosts / a.beta)
    per_cycle += a.alpha * 2 * math.log2(ranks) + 8.0 * sizes[-1] / a.beta
    per_setup = 0.0
    for n in sizes[1:]:
        nbr, ghosts = coarse_level_comm(n, ranks, a.amg_stencil)
        per_setup += a.amg_setup_exchanges * (nbr * a.alpha + 8.0 * a.amg_setup_doubles * ghosts / a.beta)
        per_setup += a.amg_setup_reductions * a.alpha * 2 * math.log2(ranks)
    return counts.vcycles * per_cycle + counts.setups * per_setup


# ---------------------------------------------------------------- the model

def estimate(part, a):
    """One row of the table for one measured partition."""
    p, cells = part["n_parts"], part["cells"]
    c = step_counts(a)
    compute = a.t_cell * part["owned_max"]
    halo = 0.0 if p == 1 else c.exchanges * part["neighbours_max"] * a.alpha + 8.0 * c.doubles * part["ghosts_max"] / a.beta
    reduce = 0.0 if p == 1 else c.reductions * a.alpha * 2 * math.log2(p)
    coarse = t_coarse(cells, p, c, a)
    total = compute + halo + reduce + coarse
    speedup = a.t_cell * cells / total
    return dict(p=p, cells_per_rank=cells / p, ghost_fraction=part["ghosts_total"] / cells,
                nbr_max=part["neighbours_max"], nbr_mean=part["neighbours_mean"], owned_max=part["owned_max"],
                ghosts_max=part["ghosts_max"], compute=compute, halo=halo, reduce=reduce, coarse=coarse,
                total=total, speedup=speedup, efficiency=speedup / p, partition_s=part["partition_s"],
                imbalance=part["imbalance"])


def threshold(rows, level=0.5):
    """Cells per rank where the efficiency falls through `level` (log-linear between the bracketing rank
    counts), as text: the value, or a bound when the rows do not bracket it."""
    rows = sorted(rows, key=lambda r: r["p"])
    if rows[0]["efficiency"] < level:
        return f"above {rows[0]['cells_per_rank']:,.0f}"
    for a, b in zip(rows, rows[1:]):
        if a["efficiency"] >= level > b["efficiency"]:
            t = (a["efficiency"] - level) / (a["efficiency"] - b["efficiency"])
            x = math.log(a["cells_per_rank"]) + t * (math.log(b["cells_per_rank"]) - math.log(a["cells_per_rank"]))
            return f"{math.exp(x):,.0f}"
    return f"below {rows[-1]['cells_per_rank']:,.0f}"


def crossed(rows, level=0.5):
    return any(r["efficiency"] < level for r in rows)


def variants(parts, a):
    """The 50% threshold under other assumptions (one changed at a time)."""
    out = []
    changes = [("as above", {}), ("alpha 1 us", dict(alpha=1e-6)), ("alpha 5 us", dict(alpha=5e-6)),
               ("beta 3 GB/s", dict(beta=3e9)), ("coarse stencil half-width 2", dict(amg_stencil=2)),
               ("AMG hierarchy reused (no setup per step)", dict(amg_setups=0)),
               ("1.5x the CG and BiCGStab iterations", dict(cg_iterations=1.5 * a.cg_iterations,
                                                           momentum_iterations=1.5 * a.momentum_iterations)),
               ("t_cell halved (faster cores)", dict(t_cell=a.t_cell / 2))]
    for label, change in changes:
        b = argparse.Namespace(**{**vars(a), **change})
        rows = [estimate(x, b) for x in parts]
        out.append((label, threshold(rows), [r for r in rows if r["p"] == a.last][0]))
    return out


# ---------------------------------------------------------------- the section

def table(rows, asked):
    lines = ["| ranks | cells per rank | ghost fraction | neighbours max (mean) | T_compute (ms) | T_halo (ms) | "
             "T_reduce (ms) | T_coarse (ms) | T step (ms) | speed-up | efficiency |",
             "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for r in rows:
        mark = "" if r["p"] in asked else " (beyond)"
        lines.append(f"| {r['p']}{mark} | {r['cells_per_rank']:,.0f} | {100 * r['ghost_fraction']:.1f}% | "
                     f"{r['nbr_max']:.0f} ({r['nbr_mean']:.1f}) | {1e3 * r['compute']:.1f} | {1e3 * r['halo']:.2f} | "
                     f"{1e3 * r['reduce']:.2f} | {1e3 * r['coarse']:.2f} | {1e3 * r['total']:.1f} | "
                     f"{r['speedup']:.1f} | {100 * r['efficiency']:.0f}% |")
    return "\n".join(lines)


def assumptions_text(a, c, cells):
    sizes = amg_level_sizes(cells, a)
    return f"""**Assumed** (options of the script; none measured on a cluster):

- Interconnect: latency alpha = {a.alpha * 1e6:g} us per message and bandwidth beta = {a.beta / 1e9:g} GB/s per
  rank (a typical InfiniBand/Omni-Path figure; every neighbour counted as off-node, which is pessimistic for the
  neighbours that share a node), reductions as 2 log2(P) latencies.
- Counts per time step of the laminar case ({a.outer} outer x {a.correctors} pressure correctors, from
  `cfd/solver/pimple_solver.cc` and hypre's Krylov loops): kelvin's own ghost refreshes
  {a.outer * 3 + a.outer * a.correctors * 5} (grad U, grad p and U per
  outer; rAU, HbyA, p, grad p and the cut-face fluxes per corrector); momentum {a.momentum_iterations:g} BiCGStab +
  Jacobi iterations (2 matvecs, 5 inner products each; 155 over 6 steps measured by `parallel_bench` on a 40^3 cube
  on 2 ranks on 2026-12-05); pressure {a.cg_iterations:g} CG iterations (93 over 6 steps on 2 ranks in
  `parallel_speedup`), each a matvec, 3 inner products (two-norm) and one BoomerAMG V-cycle whose every level but
  the coarsest does {a.amg_level_exchanges:g} exchanges (l1-Gauss-Seidel down and up, residual, restriction,
  interpolation). Totals: {c.exchanges:.0f} fine-level exchanges carrying {c.doubles:.0f} doubles per ghost cell,
  {c.reductions:.0f} reductions, {c.vcycles:.1f} V-cycles and {c.setups:g} AMG setup per step (kelvin rebuilds the
  hierarchy every step by default). Iteration counts are held at the 2-rank values for every P: AMG convergence
  depends on the partition (Falgout in hypre-space/hypre#39), and its growth with P is not modelled.
- hypre's coarse levels (`T_coarse`): {len(sizes)} levels for {cells:,} unknowns (first, aggressive coarsening by
  {a.amg_first_ratio:g}, then {a.amg_ratio:g} per level, coarsest at most {a.amg_coarsest:g} unknowns, solved by
  Gaussian elimination on a gathered system: one all-gather per V-cycle). On level l each rank holding rows owns a
  cube of side s_l = (rows per rank)^(1/3) and its rows couple through a stencil of half-width {a.amg_stencil:g}, so it
  talks to min(ranks with rows - 1, (1 + 2 ceil(w / s_l))^3 - 1) ranks: 26 while s_l > w, up to 124 once a rank
  holds about one row (the Galerkin operators widen on coarse levels: a BoomerAMG HMIS hierarchy printed in
  hypre-space/hypre#564 goes from 7 to over 100 nonzeros per row). Each setup is taken as {a.amg_setup_exchanges:g} exchanges of
  {a.amg_setup_doubles:g} doubles per ghost row and {a.amg_setup_reductions:g} reductions per level.
- The published behaviour this stands for. Baker, Falgout, Kolev and Yang, "Scaling hypre's multigrid solvers to
  100,000 cores", in *High-Performance Scientific Computing* (Springer, 2012; LLNL-JRNL-479591), is the study of
  BoomerAMG at scale; only its abstract was reachable from here, so no figure of it is used. What was found and is
  used qualitatively: hypre's BoomerAMG manual (HMIS coarsening with distance-two interpolation truncated to 4 or 5
  elements, kelvin's settings, is what it recommends for 3D diffusion problems, and one or two levels of
  aggressive coarsening, which kelvin also uses, "can often" add "increased scalability");
  Mitchell et al., "Parallel Performance of Algebraic Multigrid Domain Decomposition (AMG-DD)" (arXiv:1906.10575):
  communication "has become a significant bottleneck that limits the scalability of AMG as processor counts
  continue to grow"; and Falgout (hypre-space/hypre#39, 2019): speed-ups hold "as long as the per-processor problem
  size is not too small", and AMG's convergence depends on the parallel data distribution. None gives a number;
  the rule that BoomerAMG stops strong-scaling below about {a.amg_rule:,.0f} unknowns per core is an **assumption**
  of this section, used only as a cross-check of the modelled threshold, not as an input.
"""


def shares(r):
    parts = [("computation", r["compute"]), ("fine-level halo", r["halo"]), ("reductions", r["reduce"]),
             ("hypre's coarse levels", r["coarse"])]
    return ", ".join(f"{100 * t / r['total']:.0f}% {name}" for name, t in parts)


def efficiency_at(rows, cells_per_rank):
    """Efficiency at a cell count per rank, log-linear between the rows (None outside them)."""
    rows = sorted(rows, key=lambda r: -r["cells_per_rank"])
    for a, b in zip(rows, rows[1:]):
        if a["cells_per_rank"] >= cells_per_rank >= b["cells_per_rank"]:
            t = math.log(a["cells_per_rank"] / cells_per_rank) / math.log(a["cells_per_rank"] / b["cells_per_rank"])
            return a["efficiency"] + t * (b["efficiency"] - a["efficiency"])
    return None


def reading(rows, every, a, thr):
    first, last = rows[0], [r for r in rows if r["p"] == a.last][0]
    e2000 = efficiency_at(every, 2000)
    at_min = ("" if e2000 is None else
              f" At the partitioner's floor, `PartitionOptions::min_cells_per_rank` = 2,000 cells per rank, the "
              f"estimated efficiency is {100 * e2000:.0f}%.")
    comm = max([("the fine-level halo", last["halo"]), ("the reductions", last["reduce"]),
                ("hypre's coarse levels (per V-cycle and per setup)", last["coarse"])], key=lambda x: x[1])
    return (f"Reading: the time of a step on {first['p']} ranks is {shares(first)}; on {last['p']} ranks "
            f"({last['cells_per_rank']:,.0f} cells per rank) it is {shares(last)}. Computation shrinks with the "
            f"rank's share; the latency of the many small messages per step does not, and the largest such term "
            f"on {last['p']} ranks is {comm[0]}. The assumed {a.amg_rule:,.0f}-unknowns-per-core rule is to be read "
            f"against the modelled {thr}.{at_min}")


def section(a, mesh_n, rows, every, asked, var, thr):
    c = step_counts(a)
    cells = rows[0]["cells_per_rank"] * rows[0]["p"]
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    t_part = max(r["partition_s"] for r in rows)
    best = max(rows, key=lambda r: r["speedup"])
    beyond = ("Rows marked (beyond) are partitions past the asked range, shown to find where the efficiency crosses "
              "50%.\n\n" if any(r["p"] not in asked for r in rows) else "")
    lfs = " (about the size of the 2.7-2.8M-cell LFS grids)" if cells > 1.5e6 else ""
    var_lines = "\n".join(f"| {label} | {t} | {100 * last['efficiency']:.0f}% |" for label, t, last in var)
    return f"""## scaling_estimate: strong scaling from 8 to 256 ranks, on paper (issue 23, acceptance 3)

Written by `tools/bench/scaling_estimate.py` on {date}. **This is an estimate, not a cluster measurement**: the
machine has 2 cores, so nothing here ran on more than one process. The partitions are real, the communication is
modelled.

**Measured here.** blockMesh cube of {mesh_n}^3 = {cells:,.0f} hexahedra{lfs}, read and renumbered as the run layer does and cut by kelvin's own partitioner (PT-Scotch through
PETSc, `PartitionCells`) into each rank count by `tools/bench/partition_stats` on one process (at most
{t_part:.1f} s per partition). From each partition: the owned cells, the ghost cells (distinct cells of other
ranks across an internal face: the halo one exchange receives) and the neighbour ranks (messages per exchange) of
the worst rank. And t_cell = {a.t_cell * 1e6:.2f} us per cell per step: kelvin's serial 0.669 s/step on 216,000
cells in the `parallel_speedup` section above (the same cube case on this machine; taken as independent of the
mesh size, as the AMG iteration counts nearly are). For scale, the 2-rank run there, 0.381 s/step with 108,337
cells on the larger rank, is 3.52 us per owned cell, 14% above t_cell (the serial run solves U with Eigen, the ranks
with hypre, and the two ranks share the memory bandwidth of this machine).

**Model** per time step on P ranks: T(P) = T_compute + T_halo + T_reduce + T_coarse, with T_compute = t_cell x
max owned cells; T_halo = exchanges x (max neighbours x alpha + 8 B x doubles x max ghosts / beta); T_reduce =
reductions x alpha x 2 log2(P); T_coarse = hypre's AMG levels below the finest (below). Speed-up =
t_cell x cells / T(P), efficiency = speed-up / P. The rank's work on its ghost rows, memory bandwidth shared by the
cores of a node, and any overlap of communication with computation are left out.

{assumptions_text(a, c, int(round(cells)))}
{table(rows, asked)}

{beyond}**Where it stops paying.** The estimated efficiency falls below 50% at about **{thr} cells per rank**
(log-linear between the bracketing rank counts). Best estimated speed-up in the rows: {best['speedup']:.0f}x on
{best['p']} ranks. With the same measured partitions, one assumption changed at a time:

| assumption changed | 50% efficiency at (cells per rank) | efficiency on {rows[-1]['p']} ranks |
| --- | ---: | ---: |
{var_lines}

{reading(rows, every, a, thr)}
"""


def replace_section(path, name, text, after):
    """Puts the section between <!-- name:begin --> and <!-- name:end --> in `path`: replaced in place, or
    inserted after the section `after`, or appended; written atomically."""
    begin, end = f"<!-- {name}:begin -->", f"<!-- {name}:end -->"
    doc = open(path).read() if os.path.exists(path) else ""
    block = f"{begin}\n{text}{end}"
    b, e = doc.find(begin), doc.find(end)
    if b >= 0 and e > b:
        doc = doc[:b] + block + doc[e + len(end):]
    else:
        anchor = f"<!-- {after}:end -->"
        at = doc.find(anchor)
        if at >= 0:
            at += len(anchor)
            doc = doc[:at] + "\n\n" + block + doc[at:]
        else:
            doc = doc.rstrip("\n") + "\n\n" + block + "\n"
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(doc)
    os.replace(tmp, path)


# ---------------------------------------------------------------- main

def arguments():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--stats", required=True, help="the partition_stats program")
    ap.add_argument("--cells", type=int, default=128, help="cells per side of the cube (default 128: 2,097,152)")
    ap.add_argument("--parts", default="8,16,32,64,128,256", help="rank counts of the table")
    ap.add_argument("--extend", default="512,1024,2048,4096",
                    help="further rank counts, shown when the efficiency stays above 50%% within --parts")
    ap.add_argument("--work", default=None, help="work directory (the cube is reused when already there)")
    ap.add_argument("--write", help="BENCHMARKS.md to update (default: print the section)")
    m = ap.add_argument_group("model (defaults: see the section's prose)")
    m.add_argument("--t-cell", type=float, default=0.669 / 216000,
                   help="serial seconds per cell per step (BENCHMARKS.md parallel_speedup: 0.669 s on 216,000 cells)")
    m.add_argument("--alpha", type=float, default=2e-6, help="latency per message (s)")
    m.add_argument("--beta", type=float, default=10e9, help="bandwidth per rank (B/s)")
    m.add_argument("--outer", type=int, default=2)
    m.add_argument("--correctors", type=int, default=2)
    m.add_argument("--momentum-iterations", type=float, default=26.0, help="BiCGStab iterations per step, all solves")
    m.add_argument("--cg-iterations", type=float, default=15.5, help="pressure CG iterations per step, all solves")
    m.add_argument("--amg-level-exchanges", type=float, default=5.0, help="exchanges per AMG level per V-cycle")
    m.add_argument("--amg-setups", type=float, default=1.0, help="AMG setups per step")
    m.add_argument("--amg-setup-exchanges", type=float, default=10.0, help="exchanges per level per setup")
    m.add_argument("--amg-setup-doubles", type=float, default=10.0, help="doubles per ghost row in a setup exchange")
    m.add_argument("--amg-setup-reductions", type=float, default=2.0, help="reductions per level per setup")
    m.add_argument("--amg-first-ratio", type=float, default=8.0, help="coarsening ratio of the aggressive first level")
    m.add_argument("--amg-ratio", type=float, default=3.0, help="coarsening ratio of the other levels")
    m.add_argument("--amg-coarsest", type=float, default=9.0, help="largest coarsest level (unknowns)")
    m.add_argument("--amg-stencil", type=float, default=1.0, help="half-width of the coarse operators' stencils")
    m.add_argument("--amg-rule", type=float, default=1e4,
                   help="assumed unknowns per core below which BoomerAMG stops strong-scaling (cross-check only)")
    return ap.parse_args()


def main():
    a = arguments()
    asked = [int(x) for x in a.parts.split(",")]
    extra = [int(x) for x in a.extend.split(",")] if a.extend else []
    a.last = max(asked)
    work = a.work or tempfile.mkdtemp(prefix="kelvin_scaling_")
    poly_mesh = cube_poly_mesh(work, a.cells)
    parts = partitions(a.stats, poly_mesh, asked + extra)
    with open(os.path.join(work, "partitions.json"), "w") as f:
        json.dump(parts, f, indent=1)
    rows = [estimate(x, a) for x in parts]
    shown = [r for r in rows if r["p"] in asked]
    for r in rows:  # the extra rows up to the first below 50%, when the asked ones do not get there
        if r["p"] not in asked and not crossed(shown):
            shown.append(r)
    text = section(a, a.cells, shown, rows, asked, variants(parts, a), threshold(rows))
    if a.write:
        replace_section(a.write, NAME, text, AFTER)
        print(f"wrote the {NAME} section of {a.write}")
    print(text)


if __name__ == "__main__":
    main()
