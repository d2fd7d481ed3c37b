#!/usr/bin/env python3
"""Benchmark: the flat plate's friction, kelvin's k-omega SST against OpenFOAM's kOmegaSST on the same mesh
(issue 22, acceptance 4).

For each requested (Re_L, y+) the zero-pressure-gradient plate of cfd/verification/flat_plate.h is solved by
  - kelvin (`flat_plate_study`: pseudo-transient PIMPLE to its steady criterion, which also writes the mesh as a
    polyMesh), and
  - OpenFOAM v1912 simpleFoam (SIMPLE; relaxation U 0.7, p 0.3, k and omega 0.7, as kelvin's run) with kOmegaSST
    on that polyMesh: the same inflow k and omega, the same start (nu_t / nu = 10 everywhere, which trips the
    boundary layer), linear-upwind U, upwind k and omega, and the wall treatment kelvin's corresponds to
    (kqRWallFunction: zero-gradient k; omegaWallFunction: the wall cell's omega fixed at the blend of the viscous
    and log values; nutUSpaldingWallFunction: the wall's nu_t from Spalding's law, zero at y+ about 1).
The plate's C_F (one side) is compared with Schoenherr's line (the flat-plate line) and ITTC-57 (a ship-model
correlation line, reported beside it). On the wall-resolved grids (first cell at y+ 2 or less) the velocity
profile at 0.8 L of each run is read as well (kelvin's `--profile`; OpenFOAM's cell centres and fields of its
last iteration, the friction velocity from the wall cell, whose u+ = y+ at y+ about 1) and its log layer
(50 < y+ < 300) is compared with the log law (kappa 0.41, B 5.0-5.2) and with the k-omega model's log-layer
values (k+ = 1 / sqrt(beta*), omega+ y+ = 1 / (sqrt(beta*) kappa), nu_t = kappa u_tau y).

Usage: tools/bench/flat_plate_peer.py --study build/ci/tools/bench/flat_plate_study
           [--case 1e7:1:100x80 --case 1e7:1:100x80:2 ...] [--iterations 6000] [--work DIR] [--write BENCHMARKS.md]
A case is RE:YPLUS:CELLS_XxCELLS_Y[:REFINEMENT] (cells along the plate and across it, before the systematic
refinement factor of flat_plate.h, which also divides the first cell's height).
"""
import argparse
import datetime
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doublebody_study import ittc57  # noqa: E402
from pimple_vs_openfoam import HEADER, write, write_or_print  # noqa: E402
from sst_cost_bench import plate_fields, plate_schemes  # noqa: E402

NAME = "flat_plate_peer"
BASHRC = "/usr/share/openfoam/etc/bashrc"
INTENSITY, VISCOSITY_RATIO, START_RATIO = 0.01, 5.0, 10.0  # kelvin's inflow defaults and the tripping start



def schoenherr(re_):
    """Schoenherr's line 0.242 / sqrt(C_F) = log10(Re C_F), by Newton's method on x = 1 / sqrt(C_F), started from
    the ITTC-57 line."""
    x = 1.0 / math.sqrt(ittc57(re_))
    for _ in range(50):
        f = 0.242 * x - math.log10(re_ / (x * x))
        x -= f / (0.242 + 2.0 / (x * math.log(10.0)))
    return 1.0 / (x * x)


def run_kelvin(study, case, iterations, mesh_dir, log, wall_omega):
    cmd = [study, "--re", repr(case["re"]), "--y-plus", repr(case["y_plus"]), "--cells-x", str(case["cells_x"]),
           "--cells-y", str(case["cells_y"]), "--refinement", repr(case["refinement"]), "--initial-viscosity-ratio",
           repr(START_RATIO), "--max-steps", str(iterations), "--wall-omega", wall_omega, "--profile"]
    if mesh_dir:
        cmd += ["--write-poly-mesh", mesh_dir]
    env = dict(os.environ, OMPI_MCA_ess_singleton_isolated="1")
    out = subprocess.run(cmd, capture_output=True, text=True, env=env)
    with open(log, "w") as f:
        f.write(out.stdout + out.stderr)
    m = re.search(r"C_F ([0-9.eE+-]+) .*converged (\w+) after (\d+) steps .*largest residual ([0-9.eE+-]+)\), (\d+) "
                  r"cells.*plate y\+ min/mean/max ([0-9.]+)/([0-9.]+)/([0-9.]+)", out.stdout)
    if out.returncode != 0 or not m:
        sys.exit(f"{' '.join(cmd)} failed:\n{out.stdout[-2000:]}{out.stderr[-2000:]}")
    return dict(C_F=float(m.group(1)), converged=m.group(2) == "true", steps=int(m.group(3)),
                residual=float(m.group(4)), cells=int(m.group(5)), y_plus_mean=float(m.group(7)),
                profile=kelvin_profile(out.stdout))


def kelvin_profile(text):
    """The rows of flat_plate_study --profile: y+, u+, nu_t / nu, k+ and omega+ y+."""
    rows = []
    for line in text.splitlines():
        m = re.match(r"\s*y\+\s+(\S+) u\+\s+(\S+) .*nu_t/nu\s+(\S+) .* k\+\s+(\S+) omega\+ y\+\s+(\S+)", line)
        if m:
            rows.append(dict(zip(("y_plus", "u_plus", "nut_plus", "k_plus", "omega_y_plus"), map(float, m.groups()))))
    return rows


def openfoam_field(path):
    """The internalField of an ASCII OpenFOAM volScalarField or volVectorField (a list of floats or tuples)."""
    text = open(path).read()
    m = re.search(r"internalField\s+nonuniform\s+List<(\w+)>\s*(\d+)\s*\(", text)
    if not m:
        sys.exit(f"{path}: no nonuniform internalField")
    n, body = int(m.group(2)), text[m.end():]
    if m.group(1) == "vector":
        return [tuple(float(x) for x in v.split()) for v in re.findall(r"\(([^()]*)\)", body)[:n]]
    return [float(x) for x in body.split(")")[0].split()[:n]]


def openfoam_profile(d, re_, station=0.8):
    """OpenFOAM's profile at x = station L (the cell column nearest to it; wall at y = 0, U = L = 1)."""
    with open(os.path.join(d, "postProcess.log"), "w") as f:
        subprocess.run(["bash", "-c", f"source {BASHRC} >/dev/null 2>&1; cd {d} && postProcess -func "
                        "writeCellCentres -latestTime"], stdout=f, stderr=subprocess.STDOUT, check=True)
    last = max((t for t in os.listdir(d) if re.fullmatch(r"[0-9.]+", t) and t != "0"), key=float)
    fields = {n: openfoam_field(os.path.join(d, last, n)) for n in ("C", "U", "nut", "k", "omega")}
    nu = 1.0 / re_
    x = min((c[0] for c in fields["C"]), key=lambda v: abs(v - station))
    column = sorted((i for i, c in enumerate(fields["C"]) if abs(c[0] - x) < 1e-9), key=lambda i: fields["C"][i][1])
    wall = column[0]
    u_tau = math.sqrt(nu * fields["U"][wall][0] / fields["C"][wall][1])
    rows = []
    for i in column:
        y_plus = fields["C"][i][1] * u_tau / nu
        rows.append(dict(y_plus=y_plus, u_plus=fields["U"][i][0] / u_tau, nut_plus=fields["nut"][i] / nu,
                         k_plus=fields["k"][i] / u_tau ** 2, omega_y_plus=fields["omega"][i] * nu / u_tau ** 2 * y_plus))
    return rows


KAPPA, B_LOW, B_HIGH, BETA_STAR = 0.41, 5.0, 5.2, 0.09
LOG_LAYER = (50.0, 300.0)  # the y+ range of the log-law comparison
WALL_RESOLVED = 2.0  # target first-cell y+ up to which a run's profile is read


def pct(a, b):
    return f"{100 * (a / b - 1):+.2f}%"


def grid_label(case):
    """Cells along and across the plate, and the refinement factor when there is one."""
    return f"{case['cells_x']} x {case['cells_y']}" + (f", x{case['refinement']:g}" if case["refinement"] != 1 else "")


def log_layer(rows, low=LOG_LAYER[0], high=LOG_LAYER[1]):
    """The profile's log layer: the fitted kappa (slope of u+ against ln y+), the largest excursion of u+ outside
    the log law's band, and the model's log-layer quantities against their ideal values."""
    band = [r for r in rows if low < r["y_plus"] < high]
    if len(band) < 3:
        return None
    slope = statistics.linear_regression([math.log(r["y_plus"]) for r in band], [r["u_plus"] for r in band]).slope

    def outside(r):
        lo, hi = math.log(r["y_plus"]) / KAPPA + B_LOW, math.log(r["y_plus"]) / KAPPA + B_HIGH
        u = r["u_plus"]
        return 0.0 if lo <= u <= hi else (u / lo - 1 if u < lo else u / hi - 1)

    worst = max(band, key=lambda r: abs(outside(r)))
    near = lambda y: min(band, key=lambda r: abs(math.log(r["y_plus"] / y)))  # noqa: E731
    return dict(kappa=1.0 / slope, worst=outside(worst), worst_at=worst["y_plus"],
                within_3=sum(abs(outside(r)) <= 0.03 for r in band), cells=len(band),
                nut_ratio=[near(y)["nut_plus"] / (KAPPA * near(y)["y_plus"]) for y in (60.0, 250.0)],
                k_plus=near(250.0)["k_plus"], omega_y_plus=near(250.0)["omega_y_plus"])


def openfoam_case(d, mesh_dir, re_, iterations):
    nu = 1.0 / re_  # U = 1 m/s, L = 1 m
    k_in = 1.5 * INTENSITY ** 2
    w_in = k_in / (VISCOSITY_RATIO * nu)
    w_start = k_in / (START_RATIO * nu)
    os.makedirs(os.path.join(d, "constant"), exist_ok=True)
    shutil.copytree(os.path.join(mesh_dir, "constant", "polyMesh"), os.path.join(d, "constant", "polyMesh"))
    write(f"{d}/system/controlDict", HEADER.format(cls="dictionary", obj="controlDict") + f"""
application simpleFoam;
startFrom startTime; startTime 0; stopAt endTime; endTime {iterations}; deltaT 1;
writeControl timeStep; writeInterval {iterations}; purgeWrite 0; writeFormat ascii; writePrecision 12;
timeFormat general; runTimeModifiable false;
functions
{{
    plateForces {{ type forces; libs ("libforces.so"); writeControl timeStep; writeInterval 1; log yes;
        patches (plate); rho rhoInf; rhoInf 1; CofR (0 0 0); }}
}}
""")
    plate_schemes(d, "steadyState", bounded="bounded ")
    write(f"{d}/system/fvSolution", HEADER.format(cls="dictionary", obj="fvSolution") + """
solvers
{
    p { solver GAMG; smoother GaussSeidel; tolerance 1e-12; relTol 0.01; }
    "(U|k|omega)" { solver PBiCGStab; preconditioner DILU; tolerance 1e-14; relTol 0.01; }
}
SIMPLE { nNonOrthogonalCorrectors 0; consistent no; residualControl { p 1e-7; U 1e-8; "(k|omega)" 1e-8; } }
relaxationFactors { fields { p 0.3; } equations { U 0.7; "(k|omega)" 0.7; } }
""")
    write(f"{d}/constant/transportProperties",
          HEADER.format(cls="dictionary", obj="transportProperties") + f"transportModel Newtonian;\nnu {nu!r};\n")
    write(f"{d}/constant/turbulenceProperties", HEADER.format(cls="dictionary", obj="turbulenceProperties") +
          "simulationType RAS;\nRAS { RASModel kOmegaSST; turbulence on; printCoeffs on; }\n")
    plate_fields(d, True, k_in, w_in, nut_wall="nutUSpaldingWallFunction", w_start=w_start)


def run_openfoam(d, log):
    with open(log, "w") as f:
        subprocess.run(["bash", "-c", f"source {BASHRC} >/dev/null 2>&1; cd {d} && simpleFoam"], stdout=f,
                       stderr=subprocess.STDOUT, check=True)
    text = open(log).read()
    viscous = [float(v) for v in re.findall(r"Sum of forces\s*\n\s*Total\s*:.*\n\s*Pressure\s*:.*\n\s*Viscous\s*:\s*"
                                            r"\((\S+)", text)]
    iterations = len(re.findall(r"^Time = ", text, re.M))
    converged = "SIMPLE solution converged" in text
    cpu = [float(x) for x in re.findall(r"ExecutionTime = (\S+) s", text)]
    residual = max(float(x) for x in re.findall(r"Solving for (?:Ux|p|k|omega), Initial residual = ([0-9.eE+-]+)",
                                                re.split(r"^Time = ", text, flags=re.M)[-1]))
    return dict(viscous=viscous, iterations=iterations, converged=converged, cpu=cpu[-1], residual=residual)


def parse_case(spec):
    parts = spec.split(":")
    try:
        cells_x, cells_y = (int(x) for x in parts[2].split("x"))
        return dict(re=float(parts[0]), y_plus=float(parts[1]), cells_x=cells_x, cells_y=cells_y,
                    refinement=float(parts[3]) if len(parts) > 3 else 1.0)
    except (IndexError, ValueError):
        sys.exit(f"--case {spec!r}: expected RE:YPLUS:CELLS_XxCELLS_Y[:REFINEMENT], e.g. 1e7:1:100x80")


def span_of(mesh_dir):
    text = open(os.path.join(mesh_dir, "constant", "polyMesh", "points")).read()
    zs = [float(m) for m in re.findall(r"\(\S+ \S+ (\S+)\)", text)]
    return max(zs) - min(zs)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--study", required=True, help="kelvin's flat_plate_study program")
    ap.add_argument("--case", action="append", default=None, metavar="RE:YPLUS:CXxCY[:REF]",
                    help="a plate run (repeatable; default 1e7:1:100x80)")
    ap.add_argument("--iterations", type=int, default=6000, help="step limit of both codes")
    ap.add_argument("--work", default=None)
    ap.add_argument("--write", help="BENCHMARKS.md to update (default: print the section)")
    args = ap.parse_args()
    if not os.path.exists(BASHRC):
        sys.exit("OpenFOAM is not installed (Debian package 'openfoam'; run tools/setup)")
    work = args.work or tempfile.mkdtemp(prefix="kelvin_flat_plate_peer_")
    rows = []
    for spec in args.case or ["1e7:1:100x80"]:
        case = parse_case(spec)
        re_ = case["re"]
        d = os.path.join(work, spec.replace(":", "_"))
        if os.path.exists(d):
            shutil.rmtree(d)
        os.makedirs(d)
        k = run_kelvin(args.study, case, args.iterations, os.path.join(d, "mesh"), os.path.join(d, "kelvin.log"),
                       "sublayer")
        kp = run_kelvin(args.study, case, args.iterations, None, os.path.join(d, "kelvin_point.log"), "point")
        openfoam_case(os.path.join(d, "openfoam"), os.path.join(d, "mesh"), re_, args.iterations)
        f = run_openfoam(os.path.join(d, "openfoam"), os.path.join(d, "simpleFoam.log"))
        f["C_F"] = f["viscous"][-1] / (0.5 * 1.0 * 1.0 * span_of(os.path.join(d, "mesh")))
        f["profile"] = openfoam_profile(os.path.join(d, "openfoam"), re_) if case["y_plus"] <= WALL_RESOLVED else []
        rows.append((case, k, kp, f))
        print(f"{spec}: kelvin C_F {k['C_F']:.5e} (point-value wall omega {kp['C_F']:.5e}), simpleFoam {f['C_F']:.5e}, Schoenherr {schoenherr(re_):.5e}",
              flush=True)
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    lines = [f"""## flat_plate_peer: the plate's friction, kelvin's SST against OpenFOAM's on the same mesh (issue 22, acceptance 4)

Run by `tools/bench/flat_plate_peer.py` on {date}. The zero-pressure-gradient plate of
`cfd/verification/flat_plate.h` (one cell thick; the grid column gives the cells along the plate and across it, 16
more on the run-up, times the refinement factor, which also divides the first cell's height), solved by kelvin (`flat_plate_study`, pseudo-transient to its steady criterion: C_F change per
flow-through below 2e-5 and every initial residual below 1e-4) and by OpenFOAM v1912 simpleFoam kOmegaSST on the
polyMesh kelvin wrote (relaxation U 0.7, p 0.3, k and omega 0.7; kqRWallFunction, omegaWallFunction,
nutUSpaldingWallFunction; the same inflow, I = {INTENSITY:g}, nu_t / nu = {VISCOSITY_RATIO:g}, and the same tripping
start, nu_t / nu = {START_RATIO:g} everywhere). C_F is one side's friction over 1/2 rho U^2 L; the reference lines are
Schoenherr's (the flat-plate line) and ITTC-57 (a ship-model correlation line). kelvin runs twice: with its
default wall omega (the wall cell's viscous value scaled to be consistent with the discrete omega equation beyond it,
`--wall-omega sublayer`, docs/formulation.md section 8.2) and with the point value OpenFOAM's omegaWallFunction
uses (`--wall-omega point`); the last column compares the second with simpleFoam, the same treatment.

| Re_L | y+ (mean) | grid | cells | kelvin C_F | vs Schoenherr | vs ITTC-57 | kelvin steps (converged, residual) | kelvin C_F, point-value wall omega | vs Schoenherr | simpleFoam C_F | vs Schoenherr | simpleFoam iterations (converged, residual) | kelvin (point value) / simpleFoam |
| ---: | ---: | --- | ---: | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: | --- | ---: |"""]
    for case, k, kp, f in rows:
        re_ = case["re"]
        s, i = schoenherr(re_), ittc57(re_)
        grid = grid_label(case)
        lines.append(f"| {re_:.0e} | {k['y_plus_mean']:.1f} | {grid} | {k['cells']:,} | {k['C_F']:.5e} | {pct(k['C_F'], s)} | "
                     f"{pct(k['C_F'], i)} | {k['steps']} ({'yes' if k['converged'] else 'NO'}, {k['residual']:.1e}) | "
                     f"{kp['C_F']:.5e}{'' if kp['converged'] else ' (NOT converged)'} | {pct(kp['C_F'], s)} | "
                     f"{f['C_F']:.5e} | {pct(f['C_F'], s)} | {f['iterations']} ({'yes' if f['converged'] else 'no'}, "
                     f"{f['residual']:.1e}) | {kp['C_F'] / f['C_F']:.4f} |")
    lines += log_layer_table(rows)
    write_or_print(args.write, NAME, "\n".join(lines) + "\n")


def log_layer_table(rows):
    """The wall-resolved runs' log layers at 0.8 L, kelvin (both wall omegas) and simpleFoam side by side."""
    out = ["", f"The log layer at 0.8 L of the wall-resolved runs ({LOG_LAYER[0]:g} < y+ < {LOG_LAYER[1]:g}): kappa from the slope of u+ against "
           f"ln y+ (the log law's {KAPPA}); the largest excursion of u+ outside the log law's band (B {B_LOW}-{B_HIGH}) "
           "and the cells within 3% of it; nu_t / (kappa u_tau y) at y+ 60 and 250 (1 in the model's log layer); k+ "
           f"and omega+ y+ at y+ 250 (the model's log layer: {1 / math.sqrt(BETA_STAR):.3f} and "
           f"{1 / (math.sqrt(BETA_STAR) * KAPPA):.3f}).", "",
           "| Re_L | grid | run | C_F vs Schoenherr | kappa fitted | largest excursion (at y+) | cells within 3% | "
           "nu_t / (kappa u_tau y) at y+ 60, 250 | k+ | omega+ y+ |",
           "| ---: | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for case, k, kp, f in rows:
        if case["y_plus"] > WALL_RESOLVED:
            continue
        grid = grid_label(case)
        for name, run in (("kelvin", k), ("kelvin, point-value wall omega", kp), ("simpleFoam", f)):
            ll = log_layer(run["profile"])
            if ll is None:
                out.append(f"| {case['re']:.0e} | {grid} | {name} | | no profile | | | | | |")
                continue
            out.append(f"| {case['re']:.0e} | {grid} | {name} | {pct(run['C_F'], schoenherr(case['re']))} | "
                       f"{ll['kappa']:.3f} | {100 * ll['worst']:+.2f}% ({ll['worst_at']:.0f}) | "
                       f"{ll['within_3']} of {ll['cells']} | {ll['nut_ratio'][0]:.3f}, {ll['nut_ratio'][1]:.3f} | "
                       f"{ll['k_plus']:.3f} | {ll['omega_y_plus']:.3f} |")
    return out


if __name__ == "__main__":
    main()
