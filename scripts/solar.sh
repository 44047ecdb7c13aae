#!/usr/bin/env bash
# Regenerates doc/solar-system.md (and out/solar.h5): the outer solar system over 500 000 days
# with FR, A, A', C, A6 and BM at several steps. A few seconds.
#   bash scripts/solar.sh [data-file [hdf5-file]]
set -euo pipefail
cd "$(dirname "$0")/.."
FSYM_PLOTS=1 source scripts/setup.sh
source scripts/apps.sh   # fsym_app: the programs of app/
mkdir -p out doc
FSYM_GIT_COMMIT=$(git rev-parse HEAD 2>/dev/null || echo unknown)
if [ -n "$(git status --porcelain 2>/dev/null)" ]; then FSYM_GIT_COMMIT="$FSYM_GIT_COMMIT (modified)"; fi
export FSYM_GIT_COMMIT
h5=${2:-out/solar.h5}
fsym_app fsym-solar --profile release --flag "-std=f2008 -O2 -ffp-contract=off" -- "${1:-data/outer_solar_system.txt}" "$h5"
"$FSYM_PYTHON" scripts/check_h5md.py "$h5"
"$FSYM_PYTHON" scripts/report_solar.py "$h5" doc/solar-system.md
