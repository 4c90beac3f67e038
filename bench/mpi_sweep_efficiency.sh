#!/bin/bash
# SPDX-License-Identifier: BSD-3-Clause
# Parallel efficiency of a coupled sweep over MPI ranks: the same sweep of the shipped coupled scene gg3462
# (32 cells/D, about 1 s a point) at -np 1 and -np 2, one point at a time per rank (--jobs 1); prints both wall
# times and T1/(2 T2), from the whole command and from the sweep's own wall time (sweep.json, without start-up).
# Run it on an otherwise idle machine with two cores or more (about 2-3 minutes at the default 64 points).
#
# Usage: bench/mpi_sweep_efficiency.sh [POINTS] [IMCOL] (defaults: 64, build/bin/imcol)
set -euo pipefail
points=${1:-64}
imcol=${2:-build/bin/imcol}
mpirun=${MPIRUN:-mpirun}
tmp=$(mktemp -d /tmp/imcol_mpi_eff.XXXXXX)
trap 'rm -rf "$tmp"' EXIT

run() {  # ranks -> "command wall s, sweep wall s"
  local t0 t1
  t0=$(date +%s.%N)
  "$mpirun" --allow-run-as-root --oversubscribe -np "$1" "$imcol" sweep coupled/gg3462 --vary velocity --from 0.09 --to 0.15 \
    --points "$points" --jobs 1 --no-plot --no-progress --out "$tmp/np$1" > "$tmp/np$1.log"
  t1=$(date +%s.%N)
  python3 -c "import json,sys; print($t1 - $t0, json.load(open(sys.argv[1]))['wall_time_s'])" "$tmp/np$1/sweep.json"
}

read -r c1 s1 < <(run 1)
read -r c2 s2 < <(run 2)
python3 - "$points" "$c1" "$s1" "$c2" "$s2" <<'PY'
import sys
n, c1, s1, c2, s2 = int(sys.argv[1]), *map(float, sys.argv[2:])
print(f"coupled sweep, gg3462 at 32 cells/D, {n} points, --jobs 1 per rank")
print(f"  -np 1: {c1:7.1f} s command, {s1:7.1f} s sweep")
print(f"  -np 2: {c2:7.1f} s command, {s2:7.1f} s sweep")
print(f"  parallel efficiency T1/(2 T2): {c1 / (2 * c2):.1%} (command), {s1 / (2 * s2):.1%} (sweep)")
PY
