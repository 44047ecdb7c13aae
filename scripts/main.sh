#!/usr/bin/env bash
# The main job: installs what is missing, builds in release mode, runs the paper's study
# (HDF5 scenes in out/, report doc/results.md) and draws the figures into doc/figures/.
# Arguments are passed to fsym-study (default: every scene), e.g. --scene eng3f --out DIR.
set -euo pipefail
cd "$(dirname "$0")/.."
FSYM_PLOTS=1 source scripts/setup.sh
out=out
args=("$@")
for ((i = 0; i < ${#args[@]}; i++)); do
    if [ "${args[$i]}" = "--out" ] && [ $((i + 1)) -lt ${#args[@]} ]; then out=${args[$((i + 1))]}; fi
done
fpm run --profile release --flag "-std=f2008 -O3 -ffp-contract=off" fsym-study -- "$@"
"$FSYM_PYTHON" scripts/plot_figures.py "$out" doc/figures
