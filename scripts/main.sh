#!/usr/bin/env bash
# The main job: installs what is missing, builds in release mode, runs the paper's study
# (HDF5 scenes in out/), renders the report doc/results.md from them and draws the figures
# into doc/figures/ (PNG and PDF). Arguments are passed to fsym-study (default: every
# scene), e.g. --scene eng3f --out DIR; the report needs the results, scan and force-point
# scenes and is rendered when out/results.h5 exists.
set -euo pipefail
cd "$(dirname "$0")/.."
FSYM_PLOTS=1 source scripts/setup.sh
source scripts/apps.sh   # fsym_app: the programs of app/
out=out
args=("$@")
for ((i = 0; i < ${#args[@]}; i++)); do
    if [ "${args[$i]}" = "--out" ] && [ $((i + 1)) -lt ${#args[@]} ]; then out=${args[$((i + 1))]}; fi
done
FSYM_GIT_COMMIT=$(git rev-parse HEAD 2>/dev/null || echo unknown)
if [ -n "$(git status --porcelain 2>/dev/null)" ]; then FSYM_GIT_COMMIT="$FSYM_GIT_COMMIT (modified)"; fi
export FSYM_GIT_COMMIT
study=$(fsym_app_exe fsym-study --profile release --flag "-std=f2008 -O3 -ffp-contract=off")
"$study" "$@"
if [ -e "$out/results.h5" ]; then "$FSYM_PYTHON" scripts/report_results.py "$out" doc/results.md; fi
"$FSYM_PYTHON" scripts/plot_figures.py "$out" doc/figures
# H5MD 1.1 conformance of every file the study wrote (its scenes; other programs' files in
# the same directory are checked by their own scripts)
files=()
for scene in $("$study" --list); do
    if [ -e "$out/$scene.h5" ]; then files+=("$out/$scene.h5"); fi
done
"$FSYM_PYTHON" scripts/check_h5md.py "${files[@]}"
