#!/usr/bin/python3
"""Benchmark: hull friction of kelvin's SST wall treatment against OpenFOAM on the same grid.

The DTC double body (data/cases/doublebody/dtc.yaml: U = 1.668 m/s, k-omega SST,
Spalding wall law) on one of kelvin's snappyHexMesh grids (default grid 3 of
`kelvin mesh data/cases/mesh/dtc_snappy.yaml --family 3`), solved by
  - kelvin (`kelvin run`, pseudo-transient PIMPLE to its steady criterion), and
  - OpenFOAM v1912 simpleFoam (SIMPLEC) with kOmegaSST and the same wall law
    (nutUSpaldingWallFunction, omegaWallFunction, kqRWallFunction), the same
    inflow k and omega, bounded upwind k and omega, linear-upwind U with
    cell-limited gradients, slip on the free-surface plane, sides and bottom,
on the polyMesh kelvin wrote, so the hull faces are the same faces in the same
order. Compared: the viscous and pressure forces on the hull, and the wall shear
stress face by face (its x part, summed over twelve bands along the hull).
The friction line is ITTC-57 at Re = U Lpp / nu.

Usage: tools/bench/wall_friction_same_grid.py --kelvin build/ci/tools/kelvin
           [--grid build/grids/doublebody_dtc/grid3 [--grid ...]] [--work /tmp/wall_friction]
           [--iterations 1500] [--write BENCHMARKS.md] [--reuse]
Each grid runs in <work>/<grid folder name>; --reuse keeps finished runs there
(a run is finished when its final output exists). Costs a few CPU minutes on
grid 3 and about 25 on grid 1 (205k cells).
"""
import argparse
import datetime
import os
import re
import shutil
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doublebody_study import ittc57  # noqa: E402
from pimple_vs_openfoam import write_or_print  # noqa: E402

NAME = "wall_friction_same_grid"
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
CASE = os.path.join(ROOT, "data", "cases", "doublebody", "dtc.yaml")
BASHRC = "/usr/share/openfoam/etc/bashrc"
U, LPP, NU, RHO = 1.668, 5.976, 1.09e-6, 998.8
INTENSITY, VISCOSITY_RATIO = 0.01, 10.0  # the case's turbulence.inflow
SLIP = ("freeSurface", "side", "bottom")



def foam_file(cls, obj, body):
    return f"FoamFile {{ version 2.0; format ascii; class {cls}; object {obj}; }}\n{body}\n"


def field(cls, name, dims, internal, inlet, outlet, wall, slip):
    patches = f"inlet {{ {inlet} }} outlet {{ {outlet} }} hull {{ {wall} }} "
    patches += " ".join(f"{p} {{ {slip} }}" for p in SLIP)
    return foam_file(cls, name, f"dimensions {dims}; internalField {internal};\nboundaryField {{ {patches} }}")


def write_openfoam_case(work, grid, iterations):
    """An OpenFOAM case in `work` on the polyMesh of the kelvin grid `grid`."""
    if os.path.exists(work):
        shutil.rmtree(work)
    for d in ("0", "constant", "system"):
        os.makedirs(os.path.join(work, d))
    shutil.copytree(os.path.join(grid, "constant", "polyMesh"), os.path.join(work, "constant", "polyMesh"))
    k = 1.5 * (INTENSITY * U) ** 2
    omega = k / (VISCOSITY_RATIO * NU)
    u = f"uniform (-{U} 0 0)"
    files = {
        "constant/transportProperties": foam_file("dictionary", "transportProperties",
                                                  f"transportModel Newtonian; nu {NU};"),
        "constant/turbulenceProperties": foam_file(
            "dictionary", "turbulenceProperties", "simulationType RAS; RAS { RASModel kOmegaSST; turbulence on; }"),
        "0/U": field("volVectorField", "U", "[0 1 -1 0 0 0 0]", u, f"type fixedValue; value {u};",
                     f"type inletOutlet; inletValue uniform (0 0 0); value {u};", "type noSlip;", "type slip;"),
        "0/p": field("volScalarField", "p", "[0 2 -2 0 0 0 0]", "uniform 0", "type zeroGradient;",
                     "type fixedValue; value uniform 0;", "type zeroGradient;", "type zeroGradient;"),
        "0/k": field("volScalarField", "k", "[0 2 -2 0 0 0 0]", f"uniform {k}", f"type fixedValue; value uniform {k};",
                     f"type inletOutlet; inletValue uniform {k}; value uniform {k};",
                     f"type kqRWallFunction; value uniform {k};", "type zeroGradient;"),
        "0/omega": field("volScalarField", "omega", "[0 0 -1 0 0 0 0]", f"uniform {omega}",
                         f"type fixedValue; value uniform {omega};",
                         f"type inletOutlet; inletValue uniform {omega}; value uniform {omega};",
                         f"type omegaWallFunction; value uniform {omega};", "type zeroGradient;"),
        "0/nut": field("volScalarField", "nut", "[0 2 -1 0 0 0 0]", "uniform 0", "type calculated; value uniform 0;",
                       "type calculated; value uniform 0;", "type nutUSpaldingWallFunction; value uniform 0;",
                       "type calculated; value uniform 0;"),
        "system/controlDict": foam_file("dictionary", "controlDict", f"""application simpleFoam; startFrom startTime;
startTime 0; stopAt endTime; endTime {iterations}; deltaT 1; writeControl timeStep; writeInterval {iterations};
writeFormat ascii; writePrecision 10; runTimeModifiable false;
functions {{
  forces {{ type forces; libs ("libforces.so"); writeControl timeStep; writeInterval 1; patches (hull);
            rho rhoInf; rhoInf {RHO}; CofR (0 0 0); }}
  wallShearStress {{ type wallShearStress; libs ("libfieldFunctionObjects.so"); patches (hull);
                     writeControl writeTime; }}
}}"""),
        "system/fvSchemes": foam_file("dictionary", "fvSchemes", """ddtSchemes { default steadyState; }
gradSchemes { default Gauss linear; limited cellLimited Gauss linear 1; grad(U) $limited; grad(k) $limited;
  grad(omega) $limited; }
divSchemes { default none; div(phi,U) bounded Gauss linearUpwind grad(U); div(phi,k) bounded Gauss upwind;
  div(phi,omega) bounded Gauss upwind; div((nuEff*dev2(T(grad(U))))) Gauss linear; }
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
wallDist { method meshWave; }"""),
        "system/fvSolution": foam_file("dictionary", "fvSolution", """solvers {
  p { solver GAMG; smoother GaussSeidel; tolerance 1e-7; relTol 0.05; }
  "(U|k|omega)" { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-8; relTol 0.1; } }
SIMPLE { nNonOrthogonalCorrectors 1; consistent yes; }
relaxationFactors { equations { U 0.9; ".*" 0.9; } fields { p 1; } }"""),
    }
    for name, text in files.items():
        with open(os.path.join(work, name), "w") as f:
            f.write(text)


def finished_openfoam(work):
    """The wallShearStress of the last time folder of a finished run in `work`, or None."""
    times = [d for d in os.listdir(work) if d.isdigit() and os.path.exists(os.path.join(work, d, "wallShearStress"))] \
        if os.path.isdir(work) else []
    return os.path.join(work, max(times, key=int), "wallShearStress") if times else None


def run_openfoam(work, grid, iterations, reuse):
    final = finished_openfoam(work) if reuse else None
    if final is None:
        write_openfoam_case(work, grid, iterations)
        final = os.path.join(work, str(iterations), "wallShearStress")
        with open(os.path.join(work, "log.simpleFoam"), "w") as log:
            subprocess.run(["bash", "-c", f"source {BASHRC} >/dev/null 2>&1; cd {work} && simpleFoam"],
                           stdout=log, stderr=subprocess.STDOUT, check=True)
    text = open(os.path.join(work, "log.simpleFoam")).read()
    # The forces function object's "Sum of forces" blocks (not its moments').
    blocks = re.findall(r"Sum of forces\s*\n\s*Total\s*:.*\n\s*Pressure\s*:\s*\((\S+).*\n\s*Viscous\s*:\s*\((\S+)",
                        text)
    pressure = [float(p) for p, _ in blocks]
    viscous = [float(v) for _, v in blocks]
    cpu = [float(m.group(1)) for m in re.finditer(r"ExecutionTime = (\S+) s", text)]
    # OpenFOAM's wallShearStress is the stress on the fluid, kelvin's the
    # stress on the wall: the drag direction (-x, the flow's) is +x here.
    tau = foam_patch_values(final, "hull", 3)
    return dict(pressure=-pressure[-1], viscous=-viscous[-1], viscous_half=-viscous[len(viscous) // 2],
                cpu=cpu[-1], iterations=len(cpu), tau_x=tau[:, 0])


def foam_patch_values(path, patch, components):
    """The nonuniform value list of `patch` in an ASCII OpenFOAM field file."""
    text = open(path).read()
    at = text.index(patch, text.index("boundaryField"))
    start = text.index("(", text.index("nonuniform", at))
    body = text[start + 1:text.index("\n)", start)]
    return np.array(body.replace("(", " ").replace(")", " ").split(), dtype=float).reshape(-1, components)


def vtk_arrays(path):
    """The arrays of a VTK XML file kelvin writes (raw appended data: a UInt64 byte count, then the
    little-endian values), by name; the points as "points"."""
    data = open(path, "rb").read()
    start = data.index(b"<AppendedData")
    base = data.index(b"_", start) + 1
    types = {"Float64": "<f8", "Int64": "<i8", "UInt8": "u1"}
    arrays = {}
    for m in re.finditer(rb"<DataArray([^>]*)/>", data[:start]):
        attrs = dict(re.findall(r'(\w+)="([^"]*)"', m.group(1).decode()))
        offset = base + int(attrs["offset"])
        count = int(np.frombuffer(data, "<u8", 1, offset)[0])
        a = np.frombuffer(data, types[attrs["type"]], count // np.dtype(types[attrs["type"]]).itemsize, offset + 8)
        comps = int(attrs.get("NumberOfComponents", "1"))
        arrays["points" if attrs["Name"] == "Points" else attrs["Name"]] = a.reshape(-1, comps) if comps > 1 else a
    return arrays


def run_kelvin(kelvin, work, grid, reuse):
    out = os.path.join(work, "kelvin")
    if not (reuse and os.path.exists(os.path.join(out, "hull.pvd"))):
        text = open(CASE).read()
        text = re.sub(r"mesh: \{poly_mesh: [^}]*\}",
                      f"mesh: {{poly_mesh: {os.path.join(os.path.abspath(grid), 'constant', 'polyMesh')}}}", text)
        text = re.sub(r"directory: .*", f"directory: {out}", text).replace("vtu_interval: -1", "vtu_interval: 0")
        os.makedirs(work, exist_ok=True)
        case = os.path.join(work, "kelvin_case.yaml")
        with open(case, "w") as f:
            f.write(text)
        env = dict(os.environ, OMPI_MCA_ess_singleton_isolated="1")
        with open(os.path.join(work, "log.kelvin"), "w") as log:
            subprocess.run([kelvin, "run", case, "--no-progress"], stdout=log, stderr=subprocess.STDOUT, check=True,
                           env=env)
    # The serial run's whole-patch files (a run on ranks writes pieces, hull_NNNNNN_r<rank>.vtp).
    surface = sorted(f for f in os.listdir(out) if re.fullmatch(r"hull_\d+\.vtp", f))[-1]
    a = vtk_arrays(os.path.join(out, surface))
    points, conn, offsets = a["points"], a["connectivity"].astype(int), a["offsets"].astype(int)
    centres, areas = [], []
    for s, e in zip(np.concatenate([[0], offsets[:-1]]), offsets):
        v = points[conn[s:e]]
        c = v.mean(axis=0)
        n = sum(np.cross(v[i] - c, v[(i + 1) % len(v)] - c) for i in range(len(v)))
        centres.append(c)
        areas.append(0.5 * np.linalg.norm(n))
    import h5py
    with h5py.File(os.path.join(out, "history.h5"), "r") as h:
        pressure = -h["forces/hull/pressure"][-1, 0]
        viscous = -h["forces/hull/viscous"][-1, 0]
        cpu = h["cpu_time"][-1]
        steps = len(h["time"])
    return dict(pressure=pressure, viscous=viscous, cpu=cpu, steps=steps, centres=np.array(centres),
                areas=np.array(areas), tau_x=-a["wallShearStress"][:, 0])


def section(grid, k, of):
    q = 0.5 * RHO * U * U
    area = k["areas"].sum()
    cf0 = ittc57(U * LPP / NU)
    x = k["centres"][:, 0]
    edges = np.linspace(x.min(), x.max(), 13)
    bands = []
    for i in range(12):
        m = (x >= edges[i]) & (x <= edges[i + 1])
        fk, fo = (k["tau_x"][m] * k["areas"][m]).sum(), (of["tau_x"][m] * k["areas"][m]).sum()
        bands.append(f"| {x.max() - edges[i + 1]:.2f} - {x.max() - edges[i]:.2f} | {k['areas'][m].sum():.3f} | "
                     f"{fk / k['areas'][m].sum() / (0.5 * U * U):.4e} | {fo / k['areas'][m].sum() / (0.5 * U * U):.4e} | "
                     f"{fk / fo:.3f} |")
    ratio = k["tau_x"] / of["tau_x"]
    cells = re.search(r"^cells (\d+)", open(os.path.join(grid, "quality.txt")).read(), re.M).group(1)
    return f"""### `{os.path.relpath(grid, ROOT)}` ({cells} cells, {of['iterations']} SIMPLE iterations)

| | kelvin | OpenFOAM | kelvin / OpenFOAM |
| --- | ---: | ---: | ---: |
| viscous force on the hull, x (N) | {k['viscous']:.4f} | {of['viscous']:.4f} | {k['viscous'] / of['viscous']:.4f} |
| C_F / C_F0 (ITTC-57, S = {area:.4f} m^2) | {k['viscous'] / (q * area) / cf0:.3f} | {of['viscous'] / (q * area) / cf0:.3f} | |
| pressure force on the hull, x (N) | {k['pressure']:.4f} | {of['pressure']:.4f} | {k['pressure'] / of['pressure']:.4f} |
| steps / iterations | {k['steps']} (to the steady criterion) | {of['iterations']} (fixed) | |

OpenFOAM's viscous force moved by {100 * (of['viscous'] / of['viscous_half'] - 1):+.3f}% over the second half of its
iterations. Face by face, kelvin / OpenFOAM wall shear (x): percentiles 5, 25, 50, 75, 95 =
{", ".join(f"{v:.3f}" for v in np.percentile(ratio, [5, 25, 50, 75, 95]))}.

| distance from the bow (m) | area (m^2) | kelvin c_f | OpenFOAM c_f | kelvin / OpenFOAM |
| --- | ---: | ---: | ---: | ---: |
""" + "\n".join(bands) + "\n\n"


def header(reused):
    return f"""## Hull friction on the same grid: kelvin against OpenFOAM's kOmegaSST (issue #25 acceptance 2)

Run by `tools/bench/wall_friction_same_grid.py` on {datetime.datetime.utcnow():%Y-%m-%d %H:%M} UTC (serial, niced,
2 shared cores). The DTC double body (`data/cases/doublebody/dtc.yaml`, U = {U} m/s, Re = {U * LPP / NU:.3g}) on
kelvin's snappyHexMesh grids: kelvin `kelvin run` against OpenFOAM v1912 simpleFoam with kOmegaSST and the same
wall law (nutUSpaldingWallFunction), the same inflow k and omega, on the polyMesh kelvin wrote (the same hull faces
in the same order).{reused}

"""


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kelvin", required=True)
    ap.add_argument("--grid", action="append", help="a kelvin grid folder (repeatable; default: DTC grid 3)")
    ap.add_argument("--work", default="/tmp/wall_friction")
    ap.add_argument("--iterations", type=int, default=1500)
    ap.add_argument("--write", default=None)
    ap.add_argument("--reuse", action="store_true")
    args = ap.parse_args()
    grids = args.grid or [os.path.join(ROOT, "build", "grids", "doublebody_dtc", "grid3")]
    text = header(f" Finished runs in {args.work} were reused (--reuse)." if args.reuse else "")
    for grid in grids:
        work = os.path.join(args.work, os.path.basename(os.path.normpath(grid)))
        of = run_openfoam(os.path.join(work, "openfoam"), grid, args.iterations, args.reuse)
        k = run_kelvin(os.path.abspath(args.kelvin), work, grid, args.reuse)
        text += section(grid, k, of)
    write_or_print(args.write, NAME, text)


if __name__ == "__main__":
    main()
