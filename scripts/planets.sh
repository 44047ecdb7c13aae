#!/usr/bin/env bash
# The planetary race (issue 22, item 2): REBOUND's WHFast, WHFast + corrector 17, WHCKM, WHCKL,
# SABA(10,6,4), leapfrog order 4 and IAS15 (the reference) against the library's Kepler-drift
# methods, interleaved, on the outer and the inner solar system, 10^4 orbits of the innermost
# planet per run. Writes doc/planets-race-results.md, doc/planets-race.csv and
# doc/figures/planets-race.{png,pdf}; definitions and the library contract: doc/planets-race.md.
# Meant to fit in ~15 min on 2 shared cores (results page: the wall time of the run).
#   bash scripts/planets.sh [planets_race.py options, e.g. --reps 5, or --smoke: 100 orbits]
#   bash scripts/planets.sh --quick [data-file]   the library alone, without REBOUND (issue 21):
#       the outer solar system for 2000 years at h = P_Jupiter/40 with every method of the
#       catalogue run with Kepler drifts ([dh]: democratic heliocentric, else Jacobi) and the
#       best kinetic + potential method C(T+V), one line per method,
#       `planets METHOD h=P/40 maxdE=X evals=E ns_per_step=T` (E: force evaluations per step, a
#       gradient counted as one; T: min over 5 repetitions, run in turn); a minute or two
# Environment:
#   FSYM_RACE_VENV         the race's own Python environment (default
#                          ~/.cache/forward-symplectic/race-venv), REBOUND pinned below
#   FSYM_RACE_CMD          the library command template (default: the fsym-planets program built
#                          with fpm in app/, when app/fpm.toml has it; else planets_race.py's
#                          default)
#   FSYM_RACE_LIB_METHODS  library methods (comma-separated), FSYM_RACE_LIB_KS their steps P/k
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh
source scripts/apps.sh   # fsym_app: the programs of app/
if [ "${1:-}" = --quick ]; then
    data=${2:-../shared/data/outer_solar_system.txt}
    [ -f "$data" ] || data=data/outer_solar_system.txt
    lscpu 2>/dev/null | sed -n 's/^Model name: */# cpu: /p' || true
    echo "# git: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
    fsym_app fsym-planets-bench --profile release \
        --flag "-std=f2008 -O2 -march=native -ffp-contract=off" -- "$data" 2000 40 5
    exit
fi
REBOUND_VERSION=5.2.2
venv=${FSYM_RACE_VENV:-$HOME/.cache/forward-symplectic/race-venv}
if ! "$venv/bin/python" -c "import rebound, numpy, matplotlib
assert rebound.__version__ == '$REBOUND_VERSION'" >/dev/null 2>&1; then
    echo "[planets] installing REBOUND $REBOUND_VERSION, numpy and matplotlib into $venv" >&2
    python3 -m venv "$venv"
    "$venv/bin/pip" install -q "rebound==$REBOUND_VERSION" "numpy==2.4.6" "matplotlib==3.11.2"
fi
# the library side: build fsym-planets once and call the executable directly (fpm run would
# re-check the build before every one of the race's runs); without it the race says so
if [ -z "${FSYM_RACE_CMD:-}" ] && grep -q '^name = "fsym-planets"' app/fpm.toml; then
    flags="-std=f2008 -O2 -ffp-contract=off"
    if exe=$(fsym_app_exe fsym-planets --profile release --flag "$flags"); then
        args="state={state} system={system} method={method} h={h} nsteps={nsteps}"
        export FSYM_RACE_CMD="$exe race $args samples={samples}"
    else
        export FSYM_RACE_MISSING="fpm could not build fsym-planets"
    fi
elif [ -z "${FSYM_RACE_CMD:-}" ]; then
    export FSYM_RACE_MISSING="app/fpm.toml has no fsym-planets executable yet (issue 21)"
fi
export FSYM_RACE_COMMAND="bash scripts/planets.sh${*:+ $*}"
exec "$venv/bin/python" scripts/planets_race.py "$@"
