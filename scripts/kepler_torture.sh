#!/usr/bin/env bash
# Random-draw torture of the Kepler drift (fsym_kepler_drift) against a real128 reference:
# 10^6 draws over the orbit classes (elliptic, near-parabolic, parabolic, hyperbolic up to
# e = 1e4, almost rectilinear), gm 1e-10..1e10, lengths 1e-6..1e6, dt up to ~1000 periods.
# Prints per class the failures, NaN results and worst relative errors, and a last line
#   kepler-torture draws=N failures=F nan=K worst=W tol=T PASS|FAIL
# and exits non-zero on FAIL. A few minutes.
#   bash scripts/kepler_torture.sh [draws [seed [tolerance]]]
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh
out=build/kepler-torture
mkdir -p "$out"
# only the four sources it needs, with the project's flags
gfortran -std=f2008 -O2 -ffp-contract=off -J "$out" -o "$out/fsym-kepler-torture" \
    src/fsym_kinds.f90 src/fsym_status.f90 src/fsym_kepler_universal.f90 \
    app/planets/fsym_kepler_check.f90 app/planets/fsym_kepler_torture.f90
lscpu 2>/dev/null | sed -n 's/^Model name: *//p' | sed 's/^/cpu: /' || true
"$out/fsym-kepler-torture" "${1:-1000000}" "${2:-20070418}" "${3:-5e-11}"
