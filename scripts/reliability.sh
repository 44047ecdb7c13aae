#!/usr/bin/env bash
# Reliability report (issue 11): builds the core library with pFUnit in a temporary CMake
# project, runs the fuzz suites (Fortran through the four faces; C under AddressSanitizer),
# the checkpoint and guard suites and the e = 0.9999 guard study, and renders
# doc/reliability.md with scripts/reliability.py. Arguments: cases per fuzz class (default
# 2000) and seed (default 20261123). Needs pFUnit (PFUNIT_DIR or
# ~/.cache/forward-symplectic/pfunit). Exits non-zero when a suite fails.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cases=${1:-2000}
seed=${2:-20261123}
pfunit=${PFUNIT_DIR:-$HOME/.cache/forward-symplectic/pfunit}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/src" "$tmp/pf"
cp "$root"/test/test_fuzz_faces.pf "$root"/test/test_checkpoint.pf "$root"/test/test_guard.pf \
    "$tmp/pf/"
cat > "$tmp/src/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.16)
project(fsym_reliability LANGUAGES Fortran C)
enable_testing()
find_package(PFUNIT REQUIRED)
file(GLOB FSYM_CORE_SOURCES "$root/src/*.f90")
list(FILTER FSYM_CORE_SOURCES EXCLUDE REGEX "fsym_(lapack|stability)\\\\.f90\$")
add_library(fsym STATIC \${FSYM_CORE_SOURCES})
target_compile_options(fsym PRIVATE -ffp-contract=off -O2 -g)
set_target_properties(fsym PROPERTIES Fortran_MODULE_DIRECTORY \${CMAKE_BINARY_DIR}/mod)
target_include_directories(fsym PUBLIC \${CMAKE_BINARY_DIR}/mod)
foreach(n test_fuzz_faces test_checkpoint test_guard)
    add_pfunit_ctest(\${n} TEST_SOURCES $tmp/pf/\${n}.pf LINK_LIBRARIES fsym)
endforeach()
add_executable(reliability_guard $root/scripts/reliability_guard.f90)
target_compile_options(reliability_guard PRIVATE -ffp-contract=off)
target_link_libraries(reliability_guard PRIVATE fsym)
set(FSYM_ROOT $root)
add_subdirectory($root/test/fuzz fuzz)
CMAKE
echo "[reliability] building in $tmp"
cmake -S "$tmp/src" -B "$tmp/build" -DCMAKE_PREFIX_PATH="$pfunit" > "$tmp/cmake.log" 2>&1 \
    || { cat "$tmp/cmake.log"; exit 1; }
cmake --build "$tmp/build" -j 2 > "$tmp/build.log" 2>&1 || { tail -30 "$tmp/build.log"; exit 1; }
report=$tmp/fuzz.txt
: > "$report"
rc=0
run() {  # name, command...: run, record the exit status (a crash is a non-zero status)
    local name=$1; shift
    if "$@" > "$tmp/$name.log" 2>&1; then echo "$name 0" >> "$tmp/status.txt"
    else echo "$name $?" >> "$tmp/status.txt"; rc=1; tail -20 "$tmp/$name.log"; fi
}
: > "$tmp/status.txt"
echo "[reliability] fuzz, $cases cases per class, seed $seed"
run fortran_fuzz env FSYM_FUZZ_CASES="$cases" FSYM_FUZZ_SEED="$seed" FSYM_FUZZ_REPORT="$report" \
    "$tmp/build/test_fuzz_faces"
run c_fuzz "$tmp/build/fuzz/fuzz_capi" "$cases" "$seed" "$report"
run checkpoint "$tmp/build/test_checkpoint"
run guard "$tmp/build/test_guard"
run alloc "$tmp/build/fuzz/alloc_failing_step"
"$tmp/build/reliability_guard" > "$tmp/guard.txt"
: > "$tmp/solar.txt"
if command -v fpm > /dev/null 2>&1; then    # fsym-solar (HDF5) killed and resumed
    for delay in 0.4 1.0 2.0; do
        if bash "$root/test/checkpoint_solar.sh" "" "$delay" >> "$tmp/solar.txt" 2>&1; then :
        else rc=1; fi
    done
fi
python3 "$root/scripts/reliability.py" --fuzz "$report" --status "$tmp/status.txt" \
    --solar "$tmp/solar.txt" --alloc "$tmp/alloc.log" \
    --guard "$tmp/guard.txt" --cases "$cases" --seed "$seed" --out "$root/doc/reliability.md"
echo "[reliability] wrote doc/reliability.md"
exit $rc
