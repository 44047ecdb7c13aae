#!/usr/bin/env bash
# Checkpoint/restart of fsym-solar (issue 11): an uninterrupted run, then a run with
# --checkpoint-every that is killed with SIGKILL mid-run and resumed with --resume; the end
# states, energy errors and evaluation counts (hex images of their bits, --end-states) must be
# identical. Usage: bash test/checkpoint_solar.sh [path to fsym-solar] [seconds before the kill]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
exe=${1:-}
delay=${2:-1.0}
if [ -z "$exe" ]; then
    source "$root/scripts/apps.sh"   # fsym_app_exe: the programs of app/ (fpm package)
    exe=$(fsym_app_exe fsym-solar --flag "-std=f2008 -O2 -ffp-contract=off" 2>/dev/null)
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
data=$root/data/outer_solar_system.txt
"$exe" --end-states "$tmp/full.txt" "$data" "$tmp/full.h5" > "$tmp/full.log"
"$exe" --checkpoint-every 3000 --checkpoint "$tmp/ck.h5" --end-states "$tmp/cut.txt" \
    "$data" "$tmp/cut.h5" > "$tmp/cut.log" 2>&1 &
pid=$!
sleep "$delay"
kill -9 "$pid" 2>/dev/null || { echo "[checkpoint] the run ended before the kill"; exit 1; }
wait "$pid" 2>/dev/null || true
[ -f "$tmp/ck.h5" ] || { echo "[checkpoint] no checkpoint written before the kill"; exit 1; }
[ ! -f "$tmp/cut.txt" ] || { echo "[checkpoint] the killed run finished"; exit 1; }
"$exe" --resume "$tmp/ck.h5" --end-states "$tmp/resumed.txt" "$data" \
    "$tmp/res.h5" > "$tmp/resumed.log"
if cmp -s "$tmp/full.txt" "$tmp/resumed.txt"; then
    n=$(wc -l < "$tmp/full.txt")
    echo "[checkpoint] killed after ${delay}s and resumed: $n cases bitwise equal"
else
    echo "[checkpoint] resumed run differs from the uninterrupted one"
    diff "$tmp/full.txt" "$tmp/resumed.txt" | head
    exit 1
fi
