#!/usr/bin/env bash
# Programs on a full disk (issue 23): fsym-solar and fsym-study write into a small tmpfs
# (mount -t tmpfs needs root; without it the test reports itself skipped, exit 77). Each must
# exit with status 1 (not a crash: no status >= 128), print its message on standard error
# even when that is a file, leave no temporary (*.part) behind, and fsym-solar must keep its
# last good checkpoint, from which a run with space resumes to the bits of an uninterrupted
# run. Usage: bash test/full_disk.sh <fsym-solar> <fsym-study>
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
solar=$1
study=$2
data=$root/data/outer_solar_system.txt
tmp=$(mktemp -d)
mnt=$tmp/small
mkdir -p "$mnt"
cleanup() { umount "$mnt" 2>/dev/null; rm -rf "$tmp"; }
trap cleanup EXIT
fails=0
check() {   # name rc errfile: status 1, a message, no temporary left
    local name=$1 rc=$2 err=$3
    if [ "$rc" -ne 1 ]; then echo "[full-disk] $name: exit status $rc (want 1)"; fails=1; fi
    if ! grep -q "^$name: " "$err"; then echo "[full-disk] $name: no message on stderr"; fails=1; fi
    if ls "$mnt" | grep -q '\.part$'; then
        echo "[full-disk] $name: temporaries left: $(ls "$mnt" | grep '\.part$')"; fails=1
    fi
}
"$solar" --end-states "$tmp/full.txt" "$data" "$tmp/full.h5" > /dev/null || exit 1
for size in 12k 40k; do
    mount -t tmpfs -o size=$size tmpfs "$mnt" 2>/dev/null \
        || { echo "[full-disk] cannot mount a tmpfs (not root?): skipped"; exit 77; }
    "$solar" --checkpoint-every 20000 --checkpoint "$mnt/ck.h5" "$data" "$mnt/solar.h5" \
        > "$tmp/out.log" 2> "$tmp/err.log"
    rc=$?
    check fsym-solar "$rc" "$tmp/err.log"
    echo "[full-disk] fsym-solar, tmpfs of $size: status $rc: $(head -c 300 "$tmp/err.log")"
    if [ "$size" = 40k ]; then   # the checkpoints fit, the final output does not
        if [ ! -s "$mnt/ck.h5" ]; then echo "[full-disk] last checkpoint lost"; fails=1
        else
            cp "$mnt/ck.h5" "$tmp/ck.h5"
            "$solar" --resume "$tmp/ck.h5" --end-states "$tmp/resumed.txt" "$data" \
                "$tmp/res.h5" > /dev/null 2>&1
            if cmp -s "$tmp/full.txt" "$tmp/resumed.txt"; then
                echo "[full-disk] resumed from the kept checkpoint: bitwise the full run"
            else echo "[full-disk] the resumed run differs"; fails=1; fi
        fi
    fi
    umount "$mnt"
done
mount -t tmpfs -o size=16k tmpfs "$mnt"
"$study" --scene results --out "$mnt" > "$tmp/out.log" 2> "$tmp/err.log"
rc=$?
check fsym-study "$rc" "$tmp/err.log"
echo "[full-disk] fsym-study, tmpfs of 16k: status $rc: $(head -c 300 "$tmp/err.log")"
umount "$mnt"
exit $fails
