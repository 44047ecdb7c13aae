#!/usr/bin/env bash
# The test command: installs what is missing, builds, and runs every test.
#  1. the real clients (F77, C, CMake consumer) built against the installed library
#     (test/clients/run.sh; the script fails on any mismatch with the modern API);
#  2. the Fortran suite fsym-tests (library); the programs' HDF5 layer is tested by the
#     pFUnit suite in test/h5 (CMake/CTest).
# The last line sums the suites: `total: N passed, N failed`. Extra arguments (a test-name
# filter) go to the library suite.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh
flags="-std=f2008 -g -O1 -fcheck=bounds,pointer -fbacktrace"
bash test/clients/run.sh
log=$(mktemp)
trap 'rm -f "$log"' EXIT
rc=0
fpm test --flag "$flags" fsym-tests -- "$@" 2>&1 | tee "$log" || rc=1
pass=$(awk '/^[0-9]+ passed, [0-9]+ failed$/ {p += $1} END {print p + 0}' "$log")
fail=$(awk '/^[0-9]+ passed, [0-9]+ failed$/ {f += $3} END {print f + 0}' "$log")
[ "$rc" -eq 0 ] || [ "$fail" -gt 0 ] || fail=$((fail + 1))   # a suite that crashed counts
echo "total: $pass passed, $fail failed"
[ "$rc" -eq 0 ] && [ "$fail" -eq 0 ]
