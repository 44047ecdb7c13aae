#!/usr/bin/env bash
# fsym_itp_run on bad input: every case must exit non-zero with a message on standard error
# naming the program, leave no file under the final name (an older file there stays as it
# was) and no temporary (*.part). Usage: run_badinput.sh PROGRAM SCRATCH_DIR
set -u
prog=$1
dir=$2
rm -rf "$dir"
mkdir -p "$dir"
failed=0

# expect CASE-NAME FINAL-FILE ARG...: run PROGRAM ARG... and check the outcome
expect() {
    local name=$1 final=$2
    shift 2
    local rc=0
    echo old > "$f"   # an older file under the final name must survive a refused run
    "$prog" "$@" > "$dir/out.txt" 2> "$dir/err.txt" || rc=$?
    local problems=()
    [ "$rc" -ne 0 ] || problems+=("exit status 0")
    grep -q '^fsym_itp_run: ' "$dir/err.txt" || problems+=("no message 'fsym_itp_run: ...'")
    if [ -f "$final" ] && ! cmp -s "$final" "$dir/old.txt"; then
        problems+=("$final written")
    fi
    if compgen -G "$dir/*.part" > /dev/null; then
        problems+=("temporary left: $(ls "$dir"/*.part)")
    fi
    if [ ${#problems[@]} -eq 0 ]; then
        printf 'ok   %-28s exit %d: %s\n' "$name" "$rc" "$(head -n 1 "$dir/err.txt")"
    else
        printf 'FAIL %-28s %s\n' "$name" "${problems[*]}"
        failed=$((failed + 1))
    fi
}

f=$dir/run.h5
echo old > "$dir/old.txt"
expect "bad method label"      "$f" pt1d NOSUCH 0.05 30 "$f"
expect "tau = 0"               "$f" pt1d A 0 30 "$f"
expect "tau < 0"               "$f" pt1d A -0.05 30 "$f"
expect "tau not a number"      "$f" pt1d A abc 30 "$f"
expect "tau NaN"               "$f" pt1d A nan 30 "$f"
expect "tend < tau"            "$f" pt1d A 0.05 0.01 "$f"
expect "tend NaN"              "$f" pt1d A 0.05 nan "$f"
expect "unknown problem"       "$f" nosuch A 0.05 30 "$f"
expect "nstates 0"             "$f" pt1d A 0.05 30 "$f" 0
expect "nstates not a number"  "$f" pt1d A 0.05 30 "$f" two
expect "unwritable path"       "$dir/no/such/dir/run.h5" pt1d A 0.05 1 "$dir/no/such/dir/run.h5"
mkdir -p "$dir/adir"
expect "path is a directory"   "$dir/adir" pt1d A 0.05 1 "$dir/adir"
if [ ! -d "$dir/adir" ]; then
    echo "FAIL the directory given as FILE.h5 is gone"
    failed=$((failed + 1))
fi

# the control: the same call with good input succeeds and replaces the old file
echo old > "$f"
if "$prog" pt1d A 0.05 1 "$f" > "$dir/out.txt" 2> "$dir/err.txt" \
    && ! cmp -s "$f" "$dir/old.txt"; then
    echo "ok   control run                  wrote $f"
else
    echo "FAIL control run: $(cat "$dir/err.txt")"
    failed=$((failed + 1))
fi
echo "$failed failure(s)"
[ "$failed" -eq 0 ]
