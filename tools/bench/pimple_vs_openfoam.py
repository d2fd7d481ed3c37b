#!/usr/bin/env python3
"""Benchmark: kelvin's PIMPLE solver against OpenFOAM's pimpleFoam.

The same 3D transient laminar case (lid-driven cube, Re = 100) on the same
blockMesh mesh (default 80^3 = 512,000 cells), same schemes (Euler,
Gauss linear gradients, linear-upwind convection, corrected Laplacian), same
PIMPLE settings (2 outer x 2 pressure correctors, no non-orthogonal
correctors) and the same tolerances, run serially one after the other in this
script. Reports wall time per PIMPLE outer iteration per cell (from the
per-step clocks, excluding start-up) and peak memory per cell, as ratios
measured in this run, plus a perf profile of kelvin. Writes BENCHMARKS.md.

Usage: tools/bench/pimple_vs_openfoam.py --kelvin build/release/tools/kelvin [--cells 80] [--steps 6]
"""
import argparse
import datetime
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

HEADER = """FoamFile
{{
    version 2.0;
    format ascii;
    class {cls};
    object {obj};
}}
"""


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def foam_case(d, n, steps, dt, nu):
    write(f"{d}/system/controlDict", HEADER.format(cls="dictionary", obj="controlDict") + f"""
application pimpleFoam;
startFrom startTime; startTime 0; stopAt endTime; endTime {steps * dt};
deltaT {dt}; writeControl timeStep; writeInterval 100000; purgeWrite 0;
writeFormat binary; writePrecision 17; writeCompression off; timeFormat general;
runTimeModifiable false;
""")
    write(f"{d}/system/blockMeshDict", HEADER.format(cls="dictionary", obj="blockMeshDict") + f"""
scale 1;
vertices ( (0 0 0) (1 0 0) (1 1 0) (0 1 0) (0 0 1) (1 0 1) (1 1 1) (0 1 1) );
blocks ( hex (0 1 2 3 4 5 6 7) ({n} {n} {n}) simpleGrading (1 1 1) );
boundary (
  lid {{ type wall; faces ((3 7 6 2)); }}
  walls {{ type wall; faces ((0 4 7 3) (1 2 6 5) (0 1 5 4) (0 3 2 1) (4 5 6 7)); }}
);
""")
    write(f"{d}/system/fvSchemes", HEADER.format(cls="dictionary", obj="fvSchemes") + """
ddtSchemes { default Euler; }
gradSchemes { default Gauss linear; }
divSchemes { default none; div(phi,U) Gauss linearUpwind grad(U); div((nuEff*dev2(T(grad(U))))) Gauss linear; }
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
""")
    write(f"{d}/system/fvSolution", HEADER.format(cls="dictionary", obj="fvSolution") + """
solvers
{
    p { solver GAMG; smoother GaussSeidel; tolerance 1e-6; relTol 0.01; }
    pFinal { $p; relTol 0; }
    "(U|UFinal)" { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-6; relTol 0; }
}
PIMPLE { nOuterCorrectors 2; nCorrectors 2; nNonOrthogonalCorrectors 0; momentumPredictor yes; pRefCell 0; pRefValue 0; }
relaxationFactors { equations { ".*" 1; } }
""")
    write(f"{d}/constant/transportProperties",
          HEADER.format(cls="dictionary", obj="transportProperties") + f"transportModel Newtonian;\nnu {nu};\n")
    write(f"{d}/constant/turbulenceProperties",
          HEADER.format(cls="dictionary", obj="turbulenceProperties") + "simulationType laminar;\n")
    write(f"{d}/0/U", HEADER.format(cls="volVectorField", obj="U") + """
dimensions [0 1 -1 0 0 0 0];
internalField uniform (0 0 0);
boundaryField { lid { type fixedValue; value uniform (1 0 0); } walls { type noSlip; } }
""")
    write(f"{d}/0/p", HEADER.format(cls="volScalarField", obj="p") + """
dimensions [0 2 -2 0 0 0 0];
internalField uniform 0;
boundaryField { lid { type zeroGradient; } walls { type zeroGradient; } }
""")


def kelvin_case(path, poly_mesh, steps, dt, nu, out, rebuild_each_step):
    write(path, f"""# Same case as the pimpleFoam run (see tools/bench/pimple_vs_openfoam.py).
mesh:
  poly_mesh: {poly_mesh}
  renumber: true
physics: {{nu: {nu}}}
schemes: {{time: euler, gradient: gauss, convection: linear_upwind, non_orthogonal_correction: true}}
solution:
  n_outer: 2
  n_correctors: 2
  n_non_orthogonal: 0
  momentum: {{solver: bicgstab, relative_tolerance: 1.0e-6}}
  pressure: {{solver: pcg_amg, relative_tolerance: 1.0e-2, final_relative_tolerance: 1.0e-6,
             rebuild_each_step: {str(rebuild_each_step).lower()}}}
time: {{dt: {dt}, end: {steps * dt}}}
boundary:
  lid: {{U: {{type: fixedValue, value: [1, 0, 0]}}, p: {{type: zeroGradient}}}}
  walls: {{U: {{type: noSlip}}, p: {{type: zeroGradient}}}}
output: {{directory: {out}, vtu_interval: -1, checkpoint_interval: -1}}
""")


def run(cmd, env=None, log=None):
    """Runs cmd, returns (wall seconds, peak RSS in bytes, output)."""
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env, text=True)
    out = proc.stdout.read()
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    if log:
        with open(log, "w") as f:
            f.write(out)
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"command failed: {' '.join(cmd)}\n{out[-3000:]}")
    return wall, usage.ru_maxrss * 1024, out


def foam(d, app, log):
    return run(["bash", "-c", f"source /usr/share/openfoam/etc/bashrc >/dev/null 2>&1; cd {d} && exec {app}"], log=log)


def h5_column(path, name):
    out = subprocess.run(["h5dump", "-d", name, "-w", "0", "-y", path], capture_output=True, text=True, check=True).stdout
    start = out.index("DATA {") + 6
    body = out[start:out.index("}", start)]
    return [float(x) for x in re.split(r"[,\s]+", body.strip()) if x]


def replace_section(path, name, section):
    """Replaces this benchmark's section of BENCHMARKS.md (between
    <!-- name:begin --> and <!-- name:end -->) or appends it; atomic."""
    begin, end = f"<!-- {name}:begin -->", f"<!-- {name}:end -->"
    text = open(path).read() if os.path.exists(path) else ""
    block = f"{begin}\n{section}{end}"
    b, e = text.find(begin), text.find(end)
    if b >= 0 and e > b:
        text = text[:b] + block + text[e + len(end):]
    else:
        if not text:
            text = "# Benchmarks\n\nFigures measured on the project's 2-core Debian 12 machine.\n"
        text += "\n" + block + "\n"
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def write_or_print(path, name, section):
    """Replaces the section in `path` when one is given, else prints it."""
    if path:
        replace_section(path, name, section)
    else:
        print(section)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kelvin", required=True, help="path to the kelvin program")
    ap.add_argument("--cells", type=int, default=80, help="cells per side (default 80: 512,000 cells)")
    ap.add_argument("--steps", type=int, default=6, help="time steps (the first is excluded from the timing)")
    ap.add_argument("--output", default="BENCHMARKS.md")
    ap.add_argument("--work", default=None, help="work directory (default: a temporary one)")
    args = ap.parse_args()
    if not os.path.exists("/usr/share/openfoam/etc/bashrc"):
        sys.exit("OpenFOAM is not installed (Debian package 'openfoam'; run tools/setup)")
    n, steps, nu = args.cells, args.steps, 0.01
    dt = 0.4 / n  # Courant number 0.4 at the lid
    work = args.work or tempfile.mkdtemp(prefix="kelvin_bench_")
    foam_dir = os.path.join(work, "openfoam")
    foam_case(foam_dir, n, steps, dt, nu)
    foam(foam_dir, "blockMesh", os.path.join(work, "blockMesh.log"))
    cells = n ** 3

    # pimpleFoam.
    of_wall, of_rss, of_log = foam(foam_dir, "pimpleFoam", os.path.join(work, "pimpleFoam.log"))
    exec_times = [float(x) for x in re.findall(r"ExecutionTime = ([0-9.eE+-]+) s", of_log)]
    of_outer = (exec_times[-1] - exec_times[0]) / ((len(exec_times) - 1) * 2)

    # kelvin on the same polyMesh: AMG hierarchy rebuilt every time step (the
    # default, bit-identical restarts) and kept across steps until the CG
    # iteration count grows by 20%.
    env = dict(os.environ, OMPI_MCA_ess_singleton_isolated="1")
    kelvin = {}
    for label, rebuild in (("rebuild", True), ("reuse", False)):
        kcase = os.path.join(work, "kelvin_" + label, "case.yaml")
        kout = os.path.join(work, "kelvin_" + label, "out")
        kelvin_case(kcase, os.path.join(foam_dir, "constant", "polyMesh"), steps, dt, nu, kout, rebuild)
        k_wall, k_rss, _ = run([args.kelvin, "run", "--no-progress", kcase], env=env,
                               log=os.path.join(work, f"kelvin_{label}.log"))
        hist = os.path.join(kout, "history.h5")
        cpu = h5_column(hist, "/cpu_time")
        outer = h5_column(hist, "/outer_iterations")
        kelvin[label] = dict(case=kcase, wall=k_wall, rss=k_rss, outer=(cpu[-1] - cpu[0]) / sum(outer[1:]),
                             p_iters=h5_column(hist, "/pressure_iterations"))
    kcase = kelvin["rebuild"]["case"]

    # Profile of kelvin (perf, when available).
    profile = "perf not available"
    if shutil.which("perf"):
        data = os.path.join(work, "perf.data")
        subprocess.run(["perf", "record", "-F", "499", "-g", "-o", data, args.kelvin, "run", "--no-progress",
                        "-o", os.path.join(work, "kelvin", "out_perf"), kcase],
                       env=env, capture_output=True, check=True)
        rep = subprocess.run(["perf", "report", "-i", data, "--no-children", "--sort", "symbol", "--stdio",
                              "--percent-limit", "1.5", "-g", "none"], capture_output=True, text=True).stdout
        profile = "\n".join(re.sub(r"[\s-]+$", "", l) for l in rep.splitlines() if re.match(r"^\s+[0-9.]+%", l))

    kr, ku = kelvin["rebuild"], kelvin["reuse"]
    cpu = subprocess.run(["bash", "-c", "grep -m1 'model name' /proc/cpuinfo | cut -d: -f2"], capture_output=True,
                         text=True).stdout.strip()
    foam_version = re.search(r"Build\s*:\s*(.+)", of_log)
    text = f"""## PIMPLE: kelvin vs OpenFOAM pimpleFoam (3D lid-driven cube, laminar)

Run by `tools/bench/pimple_vs_openfoam.py` on {datetime.datetime.utcnow():%Y-%m-%d %H:%M} UTC, {cpu},
one core each, one after the other. The machine is shared, so only the ratios measured in this one run are
meaningful.

Case: unit cube, lid speed 1 m/s, nu = {nu} m^2/s (Re = 100), {n}^3 = {cells:,} hexahedra from blockMesh (the same
`constant/polyMesh` is read by both), dt = {dt:g} s (Courant 0.4), {steps} time steps, PIMPLE with 2 outer x 2 pressure
correctors, no non-orthogonal correctors; Euler, Gauss linear gradients, linear-upwind convection, corrected
Laplacian. Tolerances: momentum 1e-6; pressure 1e-2 relative in the intermediate correctors and 1e-6 in the final one.
Pressure solvers: kelvin CG + hypre BoomerAMG (HMIS, ext+i Pmax 4, aggressive level 1, l1-GS 13/14, fresh setup each
step); pimpleFoam GAMG (its usual choice; PCG + DIC is slower there). Momentum: kelvin BiCGStab + Jacobi,
pimpleFoam symmetric Gauss-Seidel. OpenFOAM {foam_version.group(1) if foam_version else '(version unknown)'}.
The first time step is excluded from the per-iteration times. pimpleFoam also evaluates the explicit
`div(nuEff*dev2(T(grad(U))))` term, which kelvin omits (it vanishes for constant nu and a solenoidal U).

| | pimpleFoam | kelvin (AMG setup every step) | kelvin (AMG setup reused) |
| --- | --- | --- | --- |
| CPU time per outer iteration per cell | {of_outer / cells * 1e6:.3f} us | {kr['outer'] / cells * 1e6:.3f} us | {ku['outer'] / cells * 1e6:.3f} us |
| speed-up over pimpleFoam (target >= 1.5) | 1 | {of_outer / kr['outer']:.2f} | {of_outer / ku['outer']:.2f} |
| peak memory per cell (max RSS / cells) | {of_rss / cells:.0f} B | {kr['rss'] / cells:.0f} B | {ku['rss'] / cells:.0f} B |
| memory relative to pimpleFoam (target <= 1) | 1 | {kr['rss'] / of_rss:.2f} | {ku['rss'] / of_rss:.2f} |
| total wall time of the run (with start-up) | {of_wall:.1f} s | {kr['wall']:.1f} s | {ku['wall']:.1f} s |

Times are process CPU times between the end of the first and the last time step (pimpleFoam's `ExecutionTime`,
kelvin's `cpu_time` history), divided by the outer iterations in between.
kelvin pressure CG iterations per step (setup every step): {', '.join(str(int(x)) for x in kr['p_iters'])};
(setup reused): {', '.join(str(int(x)) for x in ku['p_iters'])}.

### Where kelvin spends its time (perf, self time by symbol, >= 1.5%)

```
{profile}
```
"""
    replace_section(args.output, "pimple", text)
    print(text)
    print(f"work directory: {work}")


if __name__ == "__main__":
    main()
