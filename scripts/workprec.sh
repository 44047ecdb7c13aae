#!/usr/bin/env bash
# Work-precision study: builds fsym-workprec in release mode, runs it (several minutes on 2
# shared cores) and renders the report and figures from its HDF5 file. Writes
# out/work-precision.h5, doc/work-precision.csv, doc/work-precision.md and
# doc/figures/work-precision-*.{png,pdf}.
#   bash scripts/workprec.sh [--nsweep N] [--reps R] [--nmax N]   (defaults 12, 6, 20000)
set -euo pipefail
cd "$(dirname "$0")/.."
FSYM_PLOTS=1 source scripts/setup.sh
source scripts/apps.sh   # fsym_app: the programs of app/
FLAGS="-O3 -march=native -funroll-loops -std=f2008 -ffp-contract=off"
cpu=$(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')
hw="$cpu, $(nproc) cores available"
FSYM_GIT_COMMIT=$(git rev-parse HEAD 2>/dev/null || echo unknown)
if [ -n "$(git status --porcelain 2>/dev/null)" ]; then FSYM_GIT_COMMIT="$FSYM_GIT_COMMIT (modified)"; fi
export FSYM_GIT_COMMIT
mkdir -p out doc/figures
fsym_app fsym-workprec --profile release --flag "$FLAGS" -- --h5 out/work-precision.h5 \
    --csv doc/work-precision.csv --hardware "$hw" --flags "$FLAGS" "$@"
"$FSYM_PYTHON" scripts/report_workprec.py out/work-precision.h5 doc/work-precision.md doc/figures
"$FSYM_PYTHON" scripts/check_h5md.py out/work-precision.h5
