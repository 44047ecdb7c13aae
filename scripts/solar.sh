#!/usr/bin/env bash
# Regenerates doc/solar-system.md (and out/solar.h5): the outer solar system over 500 000 days
# with FR, A, A', C, A6 and BM at several steps. A few seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
FSYM_PLOTS=1 source scripts/setup.sh
mkdir -p out doc
FSYM_GIT_COMMIT=$(git rev-parse HEAD 2>/dev/null || echo unknown)
export FSYM_GIT_COMMIT
fpm run --profile release --flag "-std=f2008 -O2 -ffp-contract=off" fsym-solar -- "$@"
"$FSYM_PYTHON" scripts/check_h5md.py "${3:-out/solar.h5}"
