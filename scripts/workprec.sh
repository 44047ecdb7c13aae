#!/usr/bin/env bash
# Work-precision study: builds fsym-workprec in release mode, runs it (about 5-10 minutes on
# 2 cores) and plots. Writes doc/work-precision.md, doc/work-precision.csv and
# doc/figures/work-precision*.png, and the HDF5 file out/work-precision.h5.
# Optional arguments: number of step sizes on the e = 0.6 orbit (12), on the e = 0.9 orbit (12).
set -euo pipefail
cd "$(dirname "$0")/.."
FSYM_PLOTS=1 source scripts/setup.sh
FLAGS="-O3 -march=native -funroll-loops -std=f2008 -ffp-contract=off"
cpu=$(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')
hw="$cpu, $(nproc) cores available"
comp=$(gfortran --version | head -1)
mkdir -p out doc/figures
fpm build --profile release --flag "$FLAGS" >/dev/null
fpm run --profile release --flag "$FLAGS" fsym-workprec -- \
    doc/work-precision.md doc/work-precision.csv out/work-precision.h5 "$hw" "$comp" "$FLAGS" "${1:-12}" "${2:-12}"
"$FSYM_PYTHON" scripts/plot_workprec.py doc/work-precision.csv doc/figures/work-precision.png
