#!/usr/bin/env bash
# The main job: installs what is missing, builds in release mode and runs the paper's study.
set -euo pipefail
cd "$(dirname "$0")/.."
FSYM_PLOTS=1 source scripts/setup.sh
fpm run --profile release --flag "-std=f2008" fsym-study -- "$@"
