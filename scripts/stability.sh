#!/usr/bin/env bash
# Regenerates doc/stability.md and doc/figures/stability_*.{png,pdf} (issue 5): builds in
# release mode, runs the stability study (HDF5 to out/stability.h5), renders the page with
# scripts/report_stability.py and plots with scripts/plot_stability.py.
#   bash scripts/stability.sh [--periods N] [--nmax N] [--doc FILE.md]
#   (defaults 10000, 524288, doc/stability.md; the 1e6-period page is
#    bash scripts/stability.sh --periods 1000000 --doc doc/stability-long-run.md)
set -euo pipefail
cd "$(dirname "$0")/.."
FSYM_PLOTS=1 source scripts/setup.sh
source scripts/apps.sh   # fsym_app: the programs of app/
doc=doc/stability.md
args=()
while [ $# -gt 0 ]; do
    if [ "$1" = "--doc" ] && [ $# -ge 2 ]; then doc=$2; shift 2; else args+=("$1"); shift; fi
done
mkdir -p out doc/figures
FSYM_GIT_COMMIT=$(git rev-parse HEAD 2>/dev/null || echo unknown)
if [ -n "$(git status --porcelain 2>/dev/null)" ]; then FSYM_GIT_COMMIT="$FSYM_GIT_COMMIT (modified)"; fi
export FSYM_GIT_COMMIT
fsym_app fsym-stability --profile release --flag "-std=f2008 -O3 -ffp-contract=off" -- \
    --out out/stability.h5 "${args[@]}"
"$FSYM_PYTHON" scripts/check_h5md.py out/stability.h5
"$FSYM_PYTHON" scripts/report_stability.py out/stability.h5 "$doc"
"$FSYM_PYTHON" scripts/plot_stability.py out/stability.h5 doc/figures
