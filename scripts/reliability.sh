#!/usr/bin/env bash
# Reliability report (issues 11 and 23): builds the core library with pFUnit in a temporary
# CMake project (and, when MPI with mpi_f08 is found, the MPI agreement check), runs the fuzz
# suites (Fortran through the four faces, with systems of 1 to 150 bodies; C under
# AddressSanitizer), the checkpoint, guard and re-entrancy suites, the e = 0.9999 guard study
# and scan, the MPI agreement cases (2 and 3 ranks, each under a 60 s timeout: a hang counts),
# and, with fpm, fsym-solar killed and resumed, its damaged checkpoint files and the
# programs on a full disk (a small tmpfs; needs root). It then builds the fuzz suite once more
# against a copy of src/ with a planted defect (the kernel skips the restore of q and v after
# a failed step for arrays of 64 values or more; src/ itself is never touched) and records how
# many cases catch it. scripts/reliability.py renders doc/reliability.md. Arguments: cases
# per fuzz class (default 2000) and seed (default 20261123). Needs pFUnit (PFUNIT_DIR or
# ~/.cache/forward-symplectic/pfunit). Exits non-zero when a suite fails.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
venv=${FSYM_VENV:-$HOME/.cache/forward-symplectic/venv}
[ -x "$venv/bin/fpm" ] && PATH="$venv/bin:$PATH"      # fpm of scripts/setup.sh
cases=${1:-2000}
seed=${2:-20261123}
pfunit=${PFUNIT_DIR:-$HOME/.cache/forward-symplectic/pfunit}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/src" "$tmp/pf" "$tmp/planted"
cp "$root"/test/test_fuzz_faces.pf "$root"/test/test_checkpoint.pf "$root"/test/test_guard.pf \
    "$root"/test/test_reentry.pf "$tmp/pf/"
# the planted defect, in a copy of src/: no restore after a failed step from 64 values up
cp -r "$root/src" "$tmp/planted/src"
python3 - "$tmp/planted/src/fsym_kernel.f90" <<'PY'
import sys
p = sys.argv[1]
s = open(p).read()
old = "        if (ks%active) then\n            if (ks%qsaved) q = w(:, :, ks%iq0)"
new = ("        if (ks%active .and. ks%d * ks%n < 64) then   ! planted defect\n"
       "            if (ks%qsaved) q = w(:, :, ks%iq0)")
if s.count(old) != 1:
    sys.exit("reliability.sh: the restore in fsym_kernel_abort was not found; update the plant")
open(p, "w").write(s.replace(old, new))
PY
cat > "$tmp/src/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.16)
project(fsym_reliability LANGUAGES Fortran C)
enable_testing()
find_package(PFUNIT REQUIRED)
file(GLOB FSYM_CORE_SOURCES "\${FSYM_SRC}/*.f90")
list(FILTER FSYM_CORE_SOURCES EXCLUDE REGEX "fsym_(lapack|stability)\\\\.f90\$")
add_library(fsym STATIC \${FSYM_CORE_SOURCES})
target_compile_options(fsym PRIVATE -ffp-contract=off -O2 -g)
set_target_properties(fsym PROPERTIES Fortran_MODULE_DIRECTORY \${CMAKE_BINARY_DIR}/mod)
target_include_directories(fsym PUBLIC \${CMAKE_BINARY_DIR}/mod)
# the test suites' shared modules (fsym_test_models, ...): test/support
add_library(fsym_test_support STATIC $root/test/support/fsym_test_methods.f90
    $root/test/support/fsym_test_models.f90 $root/test/support/fsym_test_sun_planets.f90)
target_compile_options(fsym_test_support PRIVATE -ffp-contract=off)
set_target_properties(fsym_test_support PROPERTIES
    Fortran_MODULE_DIRECTORY \${CMAKE_BINARY_DIR}/mod_support)
target_include_directories(fsym_test_support PUBLIC \${CMAKE_BINARY_DIR}/mod_support)
target_link_libraries(fsym_test_support PUBLIC fsym PFUNIT::funit)
foreach(n \${FSYM_SUITES})
    add_pfunit_ctest(\${n} TEST_SOURCES $tmp/pf/\${n}.pf LINK_LIBRARIES fsym_test_support fsym)
endforeach()
if(FSYM_EXTRAS)
    add_executable(reliability_guard $root/scripts/reliability_guard.f90)
    target_compile_options(reliability_guard PRIVATE -ffp-contract=off)
    target_link_libraries(reliability_guard PRIVATE fsym)
    set(FSYM_ROOT $root)
    add_subdirectory($root/test/fuzz fuzz)
    find_package(MPI COMPONENTS Fortran)
    if(MPI_Fortran_FOUND AND MPI_Fortran_HAVE_F08_MODULE)
        add_library(fsym_mpi STATIC $root/mpi/fsym_scale_setup.f90 $root/mpi/fsym_mpi_nbody.f90
                    $root/mpi/fsym_mpi_agree.f90)
        target_compile_options(fsym_mpi PRIVATE -ffp-contract=off)
        target_link_libraries(fsym_mpi PUBLIC fsym MPI::MPI_Fortran)
        add_executable(fsym_mpi_agree_check $root/mpi/fsym_mpi_agree_check.f90
            $root/mpi/fsym_mpi_test_models.f90)
        target_link_libraries(fsym_mpi_agree_check PRIVATE fsym_mpi)
    endif()
endif()
CMAKE
echo "[reliability] building in $tmp"
cmake -S "$tmp/src" -B "$tmp/build" -DCMAKE_PREFIX_PATH="$pfunit" -DFSYM_SRC="$root/src" \
    -DFSYM_SUITES="test_fuzz_faces;test_checkpoint;test_guard;test_reentry" -DFSYM_EXTRAS=ON \
    > "$tmp/cmake.log" 2>&1 || { cat "$tmp/cmake.log"; exit 1; }
cmake --build "$tmp/build" -j 2 > "$tmp/build.log" 2>&1 || { tail -30 "$tmp/build.log"; exit 1; }
cmake -S "$tmp/src" -B "$tmp/build-planted" -DCMAKE_PREFIX_PATH="$pfunit" \
    -DFSYM_SRC="$tmp/planted/src" -DFSYM_SUITES="test_fuzz_faces" -DFSYM_EXTRAS=OFF \
    > "$tmp/cmake-planted.log" 2>&1 || { cat "$tmp/cmake-planted.log"; exit 1; }
cmake --build "$tmp/build-planted" -j 2 > "$tmp/build-planted.log" 2>&1 \
    || { tail -30 "$tmp/build-planted.log"; exit 1; }
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
run reentry env FSYM_FUZZ_REPORT="$report" "$tmp/build/test_reentry"
run alloc "$tmp/build/fuzz/alloc_failing_step"
"$tmp/build/reliability_guard" > "$tmp/guard.txt"
# the planted defect: the same fuzz suite must fail (its report counts the cases that catch it)
echo "[reliability] fuzz against the planted defect"
if env FSYM_FUZZ_CASES="$cases" FSYM_FUZZ_SEED="$seed" FSYM_FUZZ_REPORT="$tmp/planted.txt" \
        "$tmp/build-planted/test_fuzz_faces" > "$tmp/planted.log" 2>&1; then
    echo "planted 0" >> "$tmp/status.txt"; rc=1
    echo "[reliability] the fuzz suite did NOT catch the planted defect"
else
    echo "planted $?" >> "$tmp/status.txt"
fi
# MPI agreement: every case must end (timeout 60 s) with the expected status on every rank
: > "$tmp/mpi.txt"
if [ -x "$tmp/build/fsym_mpi_agree_check" ] && command -v mpirun > /dev/null 2>&1; then
    for np in 2 3; do
        for c in nan model h label method none; do
            t0=$(date +%s.%N)
            if OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 \
                timeout 60 mpirun --oversubscribe -np $np "$tmp/build/fsym_mpi_agree_check" \
                case=$c > "$tmp/mpi1.log" 2>&1; then r=0; else r=$?; rc=1; fi
            t1=$(date +%s.%N)
            echo "mpi $np $c $r $(python3 -c "print('%.1f' % ($t1 - $t0))")" >> "$tmp/mpi.txt"
        done
    done
fi
: > "$tmp/solar.txt"; : > "$tmp/files.txt"; : > "$tmp/disk.txt"
if command -v fpm > /dev/null 2>&1; then    # fsym-solar (HDF5) killed and resumed
    flags="-std=f2008 -O2 -ffp-contract=off"
    source "$root/scripts/apps.sh"   # fsym_app_exe: the programs of app/
    solar=$(fsym_app_exe fsym-solar --flag "$flags" 2>/dev/null)
    study=$(fsym_app_exe fsym-study --flag "$flags" 2>/dev/null)
    for delay in 0.4 1.0 2.0; do
        if bash "$root/test/checkpoint_solar.sh" "$solar" "$delay" >> "$tmp/solar.txt" 2>&1
        then :; else rc=1; fi
    done
    bash "$root/test/checkpoint_file.sh" "$solar" 100 > "$tmp/files.txt" 2>&1 || rc=1
    set +e
    bash "$root/test/full_disk.sh" "$solar" "$study" > "$tmp/disk.txt" 2>&1
    r=$?
    set -e
    if [ $r -eq 77 ]; then echo "[full-disk] skipped: no tmpfs" >> "$tmp/disk.txt"
    elif [ $r -ne 0 ]; then rc=1; fi
fi
# keep the raw outputs (build/ is git-ignored): the page can be rendered again from them
keep=$root/build/reliability-last
rm -rf "$keep"; mkdir -p "$keep"
cp "$report" "$tmp"/status.txt "$tmp"/solar.txt "$tmp"/guard.txt "$tmp"/mpi.txt \
    "$tmp"/files.txt "$tmp"/disk.txt "$keep/" 2>/dev/null || true
cp "$tmp"/planted.txt "$tmp"/alloc.log "$keep/" 2>/dev/null || true
python3 "$root/scripts/reliability.py" --fuzz "$report" --status "$tmp/status.txt" \
    --solar "$tmp/solar.txt" --alloc "$tmp/alloc.log" --guard "$tmp/guard.txt" \
    --planted "$tmp/planted.txt" --mpi "$tmp/mpi.txt" --files "$tmp/files.txt" \
    --disk "$tmp/disk.txt" --cases "$cases" --seed "$seed" --out "$root/doc/reliability.md"
echo "[reliability] wrote doc/reliability.md"
exit $rc
