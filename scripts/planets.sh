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
#   bash scripts/planets.sh --eps-split [data-file]   the same at h = P_Jupiter/40 with every
#       planet's mass times s = 1, 1/2, 1/4, 1/8 (one repetition): the part of max|dE/E| linear
#       in the mass ratio eps scales as s, the eps^2 part as s^2; lines
#       `epsplit METHOD s=S maxdE=X maxdE/s=Y` and, from the two smallest s (Y = a + b s),
#       `epsplit METHOD linear=a eps2_at_s1=b` (a: the eps-linear part at the real masses)
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
if [ "${1:-}" = --eps-split ]; then
    data=${2:-../shared/data/outer_solar_system.txt}
    [ -f "$data" ] || data=data/outer_solar_system.txt
    lscpu 2>/dev/null | sed -n 's/^Model name: */# cpu: /p' || true
    echo "# git: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
    exe=$(fsym_app_exe fsym-planets-bench --profile release \
        --flag "-std=f2008 -O2 -march=native -ffp-contract=off")
    lines=$(for s in 1 0.5 0.25 0.125; do
        "$exe" "$data" 2000 40 1 "$s" | awk -v s="$s" '$1 == "planets" && $4 == "maxdE=" {
            printf "epsplit %s s=%s maxdE=%.3e maxdE/s=%.3e\n", $2, s, $5, $5 / s }'
    done)
    printf '%s\n' "$lines"
    printf '%s\n' "$lines" | awk '{ split($3, a, "="); split($5, y, "=")
            if (a[2] == 0.25) y4[$2] = y[2]; if (a[2] == 0.125) y8[$2] = y[2] }
        END { for (k in y8) printf "epsplit %s linear=%.3e eps2_at_s1=%.3e\n", k,
              2 * y8[k] - y4[k], (y4[k] - y8[k]) / 0.125 }' | sort
    exit
fi
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
