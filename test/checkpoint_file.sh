#!/usr/bin/env bash
# Checkpoint FILES of fsym-solar (issue 23): a checkpoint that is truncated, has a byte
# changed anywhere, is another HDF5 file or no HDF5 at all must be refused by --resume with
# exit status 1 and a message naming the failed check, never a crash (status >= 128) and
# never a run that resumes to other results: a resumed run either is refused or ends with the
# bits of the uninterrupted run (a byte of HDF5 padding changes nothing). Also: two jobs
# writing checkpoints to the same path at once both finish (temporaries unique per process).
# Usage: bash test/checkpoint_file.sh <fsym-solar> [byte changes, default 60]
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
exe=$1
flips=${2:-60}
data=$root/data/outer_solar_system.txt
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$exe" --end-states "$tmp/full.txt" "$data" "$tmp/full.h5" > /dev/null || exit 1
# a checkpoint late in the run (the last one written stays on disk)
"$exe" --checkpoint-every 20000 --checkpoint "$tmp/ck.h5" "$data" "$tmp/x.h5" > /dev/null \
    || exit 1
size=$(stat -c %s "$tmp/ck.h5")
refused=0; same=0; bad=0
try() {   # name file: resume from file; refused (status 1 + message) or bitwise the full run
    local name=$1 file=$2
    rm -f "$tmp/res.txt"
    "$exe" --resume "$file" --end-states "$tmp/res.txt" "$data" "$tmp/res.h5" \
        > /dev/null 2> "$tmp/err.log"
    local rc=$?
    if [ "$rc" -eq 1 ] && grep -q "^fsym-solar: " "$tmp/err.log"; then
        refused=$((refused + 1))
        [ -n "${3:-}" ] && echo "[ckpt-file] $name: $(head -c 200 "$tmp/err.log")"
    elif [ "$rc" -eq 0 ] && cmp -s "$tmp/full.txt" "$tmp/res.txt"; then
        same=$((same + 1))
    else
        bad=$((bad + 1)); echo "[ckpt-file] $name: status $rc, $(head -c 300 "$tmp/err.log")"
    fi
}
try intact "$tmp/ck.h5"
[ "$same" -eq 1 ] || { echo "[ckpt-file] the intact checkpoint does not resume bitwise"; exit 1; }
same=0
for frac in 0 10 50 90 99; do
    head -c $((size * frac / 100)) "$tmp/ck.h5" > "$tmp/t.h5"
    try "truncated to $frac%" "$tmp/t.h5" say
done
try "foreign HDF5 (the output file)" "$tmp/full.h5" say
try "not HDF5 (the data file)" "$data" say
try "missing" "$tmp/none.h5" say
# byte changes spread over the file (a fixed sequence: reproducible)
seed=20261123
for k in $(seq 1 "$flips"); do
    seed=$(( (seed * 1103515245 + 12345) % 2147483648 ))
    pos=$(( seed % size ))
    cp "$tmp/ck.h5" "$tmp/f.h5"
    old=$(od -An -tu1 -j "$pos" -N1 "$tmp/f.h5" | tr -d ' ')
    new=$(( (old + 1 + seed % 255) % 256 ))
    printf "$(printf '\\%03o' "$new")" | dd of="$tmp/f.h5" bs=1 seek="$pos" conv=notrunc \
        status=none
    try "byte $pos" "$tmp/f.h5"
done
echo "[ckpt-file] $((flips + 8)) damaged checkpoints: $refused refused, $same resumed bitwise" \
     "(a byte that HDF5 does not read), $bad wrong or crashed"
# two jobs, one checkpoint path, at the same time: both finish
"$exe" --checkpoint-every 5000 --checkpoint "$tmp/shared.h5" "$data" "$tmp/a.h5" \
    > /dev/null 2> "$tmp/a.err" &
p1=$!
"$exe" --checkpoint-every 5000 --checkpoint "$tmp/shared.h5" "$data" "$tmp/b.h5" \
    > /dev/null 2> "$tmp/b.err" &
p2=$!
wait $p1; r1=$?; wait $p2; r2=$?
if [ $r1 -ne 0 ] || [ $r2 -ne 0 ]; then
    echo "[ckpt-file] two jobs on one checkpoint path: status $r1 and $r2"; bad=$((bad + 1))
else
    echo "[ckpt-file] two jobs on one checkpoint path: both finished"
fi
[ "$bad" -eq 0 ]
