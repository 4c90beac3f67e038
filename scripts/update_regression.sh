#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Regenerates data/reference/imcol_regression.csv from the shipped scenes at rtol 1e-10.
# Run it only after a deliberate model change, and say so in the commit.
set -euo pipefail
cd "$(dirname "$0")/.."
out=$(mktemp -d)
{
  echo "# imcol's own results for the shipped scenes at rtol 1e-10 (regression reference, not validation)."
  echo "# Regenerate with scripts/update_regression.sh after a deliberate model change."
  echo "scene,e,St,min_gap_m"
  for f in data/scenes/*.toml; do
    name=$(basename "$f" .toml)
    ./build/bin/imcol run "$f" --rtol 1e-10 --out "$out/$name" --quiet --no-plot
    /usr/bin/python3 - "$out/$name/summary.json" "$name" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
fmt = lambda v: "" if v is None else repr(v)
print(f"{sys.argv[2]},{fmt(s['e'])},{fmt(s['St'])},{fmt(s['min_gap_m'])}")
PY
  done
} > data/reference/imcol_regression.csv.tmp
mv data/reference/imcol_regression.csv.tmp data/reference/imcol_regression.csv
rm -rf "$out"
cat data/reference/imcol_regression.csv
