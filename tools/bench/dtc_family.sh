#!/bin/bash
# The DTC at 1.668 m/s on the three-grid snappy family, both linearizations of the free surface and the double
# body (issue 22, acceptance 2): `kelvin gci` of data/cases/resistance/dtc_fine_double_body.yaml, dtc_fine_lfs.yaml
# and dtc_fine_lfs.yaml with `linearization: local_flow`, on the grids of
# `kelvin mesh data/cases/mesh/dtc_snappy.yaml --family 3` (meshed first if missing). Finished grid runs are reused.
# tools/bench/lfs_linearization.py --report-only --write renders the table. Several hours on 2 cores.
#
# Usage: tools/bench/dtc_family.sh [kelvin] [cases...]   (default: build/ci/tools/kelvin, all three cases)
set -euo pipefail
cd "$(dirname "$0")/../.."
export OMPI_MCA_ess_singleton_isolated=1
K=${1:-build/ci/tools/kelvin}
shift || true
CASES=${*:-dtc_fine_double_body dtc_fine_lfs dtc_fine_lfs_local}
G=build/grids/doublebody_dtc
W=build/bench/dtc_family
mkdir -p "$W"
[ -f "$G/family.txt" ] || nice "$K" mesh data/cases/mesh/dtc_snappy.yaml --family 3 -o "$G" > "$W/mesh.log" 2>&1
/usr/bin/python3 - <<'PY'
import sys; sys.path.insert(0, "tools/bench")
from case_variants import variant_case
variant_case("data/cases/resistance/dtc_fine_lfs.yaml", "build/bench/dtc_family/dtc_fine_lfs_local.yaml",
             {"boundary.freeSurface.p.linearization": "local_flow"})
PY
for c in $CASES; do
  case_file=data/cases/resistance/$c.yaml
  [ "$c" = dtc_fine_lfs_local ] && case_file=$W/$c.yaml
  nice "$K" gci "$case_file" --family 3 --grids "$G" --outputs C_T,C_F,C_P --runs "$W/$c" > "$W/$c.log" 2>&1
done
