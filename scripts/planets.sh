#!/usr/bin/env bash
# Planetary benchmark (issue 21): the outer solar system (../shared/data/outer_solar_system.txt,
# else data/outer_solar_system.txt) for 2000 years at h = P_Jupiter/40 with every method of the
# catalogue run with Kepler drifts (Wisdom-Holman splitting, Jacobi coordinates; [dh]:
# democratic heliocentric) and the best kinetic + potential method, C(T+V). One line per method:
#   planets METHOD h=P/40 maxdE=X evals=E ns_per_step=T
# (E: force evaluations per step, a gradient counted as one; T: min over the repetitions, run
# in turn). A minute or two.
#   bash scripts/planets.sh --quick [data-file]     (2000 years, 5 repetitions)
#   bash scripts/planets.sh [data-file]             (20000 years, 9 repetitions)
set -euo pipefail
cd "$(dirname "$0")/.."
years=20000; reps=9
if [ "${1:-}" = --quick ]; then years=2000; reps=5; shift; fi
data=${1:-../shared/data/outer_solar_system.txt}
[ -f "$data" ] || data=data/outer_solar_system.txt
source scripts/setup.sh
lscpu 2>/dev/null | sed -n 's/^Model name: */# cpu: /p' || true
echo "# git: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$([ -n "$(git status --porcelain 2>/dev/null)" ] && echo ' (modified)')"
fpm run --profile release --flag "-std=f2008 -O2 -march=native -ffp-contract=off" \
    fsym-planets-bench -- "$data" "$years" 40 "$reps"
