#!/usr/bin/env bash
# Threads and MPI for the N-body model: bitwise checks and scaling measurements.
#
#   bash scripts/scale.sh --check
#       builds the serial and the OpenMP library with the MPI parts (CMake, build/scale/),
#       runs the serial, threaded (1, 2, 3 threads) and MPI (1, 2, 4 ranks; even and uneven
#       blocks; 2 ranks x 2 threads) runs of methods FR, A and C', compares their end states
#       bit for bit and prints `threads: bitwise identical to serial` and
#       `mpi: bitwise identical to serial` (or the first difference, exit status 1), then one
#       line `pair N=... ns/pair=X` per N of the pair benchmark (serial, one core).
#   bash scripts/scale.sh
#       the same, then the strong and weak scaling runs; rewrites doc/scaling.md (through
#       scripts/scale_report.py) from the raw results in out/scale/results.txt. A few minutes.
#
# Flags: CMake Release (-O3) with -march=native and -ffp-contract=off (the bits do not depend
# on -march without contraction; the speed does). As root, OpenMPI needs
# OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1, which this script sets.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-report}
export FSYM_MPI=1
source scripts/setup.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
# ranks waiting in a collective yield the core instead of spinning (the machine is shared)
export OMPI_MCA_mpi_yield_when_idle=1

build=build/scale
out=out/scale
mkdir -p "$out" "$build"
log="$out/build.log"
: >"$log"
for variant in serial omp; do
    omp=OFF
    [ "$variant" = omp ] && omp=ON
    cmake -S . -B "$build/$variant" -DCMAKE_BUILD_TYPE=Release -DFSYM_MPI=ON \
        -DFSYM_OPENMP=$omp -DCMAKE_Fortran_FLAGS="-march=native" >>"$log" 2>&1 \
        || { echo "cmake failed, see $log" >&2; exit 1; }
    cmake --build "$build/$variant" -j2 --target fsym_scale_bench fsym_mpi_driver >>"$log" 2>&1 \
        || { echo "build failed, see $log" >&2; exit 1; }
done
sbench=$build/serial/fsym_scale_bench
obench=$build/omp/fsym_scale_bench
sdrv=$build/serial/fsym_mpi_driver
odrv=$build/omp/fsym_mpi_driver
# --bind-to none: OpenMPI binds each rank to one core by default (for up to 2 ranks), which
# would put all OpenMP threads of a rank on that core
mpirun_np() { mpirun --oversubscribe --bind-to none -np "$@"; }

# ---- bitwise checks: end states of every run against the serial library's ----
ncheck=501
steps=4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
first_diff() {   # first_diff REF FILE LABEL -> prints nothing when identical
    local d
    if ! d=$("$sbench" mode=compare n=$ncheck a="$1" b="$2" 2>/dev/null); then
        echo "$3: ${d:-cannot compare}"
    fi
}
tdiff=""
mdiff=""
for method in FR A "C'"; do
    tag=${method//\'/p}
    ref=$tmp/serial_$tag.bin
    OMP_NUM_THREADS=1 "$sbench" mode=state n=$ncheck steps=$steps method="$method" state="$ref"
    for t in 1 2 3; do
        f=$tmp/threads${t}_$tag.bin
        OMP_NUM_THREADS=$t "$obench" mode=state n=$ncheck steps=$steps method="$method" state="$f"
        [ -n "$tdiff" ] || tdiff=$(first_diff "$ref" "$f" "method $method, $t threads")
    done
    for np in 1 2 4; do
        for blocks in even uneven; do
            f=$tmp/mpi${np}_${blocks}_$tag.bin
            OMP_NUM_THREADS=1 mpirun_np "$np" "$sdrv" n=$ncheck steps=$steps method="$method" \
                blocks=$blocks state="$f" >/dev/null
            [ -n "$mdiff" ] || mdiff=$(first_diff "$ref" "$f" "method $method, $np ranks, $blocks blocks")
        done
    done
    f=$tmp/hybrid_$tag.bin
    OMP_NUM_THREADS=2 mpirun_np 2 "$odrv" n=$ncheck steps=$steps method="$method" \
        blocks=uneven state="$f" >/dev/null
    [ -n "$mdiff" ] || mdiff=$(first_diff "$ref" "$f" "method $method, 2 ranks x 2 threads")
done
status=0
if [ -z "$tdiff" ]; then echo "threads: bitwise identical to serial"; else
    echo "threads: first difference from serial: $tdiff"; status=1; fi
if [ -z "$mdiff" ]; then echo "mpi: bitwise identical to serial"; else
    echo "mpi: first difference from serial: $mdiff"; status=1; fi

# ---- pair benchmark (serial library, one core): minimum over rounds x repetitions ----
pairs=$out/pair.txt
: >"$pairs"
for round in 1 2 3 4 5; do
    for n in 1000 4000 16000; do
        reps=7
        [ $n -ge 16000 ] && reps=3
        OMP_NUM_THREADS=1 "$sbench" mode=pair n=$n reps=$reps >>"$pairs"
    done
done
for n in 1000 4000 16000; do
    grep "^pair N=$n " "$pairs" | awk '{split($3, a, "="); print a[2], $1, $2}' | sort -g | head -1 \
        | awk '{printf "%s %s ns/pair=%s\n", $2, $3, $1}'
done
[ "$mode" = --check ] && exit $status
[ $status -eq 0 ] || { echo "bitwise checks failed: doc/scaling.md not rewritten" >&2; exit 1; }

# ---- the rest of doc/scaling.md: raw results, interleaved, then the report ----
res=$out/results.txt
{
    echo "cpu $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs) cores=$(nproc)"
    echo "load_before $(cut -d' ' -f1-3 /proc/loadavg)"
    echo "compiler $(gfortran -dumpfullversion) mpi $(mpirun --version | head -1)"
    echo "commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$([ -n "$(git status --porcelain --untracked-files=no 2>/dev/null)" ] && echo ' (modified)')"
    echo "check threads: bitwise identical to serial"
    echo "check mpi: bitwise identical to serial"
    "$sbench" mode=cost n=8
    cat "$pairs"
    for round in 1 2 3; do "$sbench" mode=bound; done
} >"$res"
# threads: the library's pair kernel on 1 and 2 threads, alternating inside one process
for round in 1 2 3 4 5; do
    echo "load $(cut -d' ' -f1 /proc/loadavg)" >>"$res"
    for n in 1000 2000 4000 16000; do
        reps=15
        [ $n -ge 16000 ] && reps=3
        "$obench" mode=tpair n=$n reps=$reps >>"$res"
    done
done
# strong scaling (fixed N) and weak scaling (N sqrt(P) for P = 2 cores: work per core fixed),
# method A (forces and the gradient term); ranks x threads = 1x1, 1x2, 2x1, 2x2
for round in 1 2 3 4 5; do
    echo "load $(cut -d' ' -f1 /proc/loadavg)" >>"$res"
    for n in 1000 4000 16000 1414 5657 22627; do
        case $n in
            1000 | 1414) s=10 ;;
            4000 | 5657) s=3 ;;
            *) s=1 ;;
        esac
        for cfg in 1x1 1x2 2x1 2x2; do
            np=${cfg%x*}
            t=${cfg#*x}
            case $n in 1414 | 5657 | 22627) [ "$cfg" = 1x1 ] && continue ;; esac
            OMP_NUM_THREADS=$t mpirun_np "$np" "$odrv" n=$n steps=$s method=A reps=1 >>"$res"
        done
    done
done
echo "load_after $(cut -d' ' -f1-3 /proc/loadavg)" >>"$res"
python3 scripts/scale_report.py "$res" doc/scaling.md
echo "wrote doc/scaling.md"
