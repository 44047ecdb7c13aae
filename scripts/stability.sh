#!/usr/bin/env bash
# Regenerates doc/stability.md and doc/figures/stability_*.png (issue 5): builds in release
# mode, runs the stability study (HDF5 to out/stability.h5) and plots it.
#   bash scripts/stability.sh [--periods N] [--nmax N]   (defaults 10000 and 524288)
set -euo pipefail
cd "$(dirname "$0")/.."
FSYM_PLOTS=1 source scripts/setup.sh
mkdir -p out doc/figures
FSYM_GIT_COMMIT=$(git rev-parse HEAD 2>/dev/null || echo unknown)
export FSYM_GIT_COMMIT
fpm run --profile release --flag "-std=f2008 -O3 -ffp-contract=off" fsym-stability -- --out out/stability.h5 \
    --doc doc/stability.md "$@"
"$FSYM_PYTHON" scripts/plot_stability.py out/stability.h5 doc/figures
"$FSYM_PYTHON" scripts/check_h5md.py out/stability.h5
