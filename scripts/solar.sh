#!/usr/bin/env bash
# Regenerates doc/solar-system.md (and out/solar.h5): the outer solar system over 500 000 days
# with FR, A, A', C, A6 and BM at several steps. A few seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh
mkdir -p out doc
fpm run --profile release --flag "-std=f2008 -O2 -ffp-contract=off" fsym-solar -- "$@"
