#!/usr/bin/env bash
# Imaginary-time benchmark (issue 26): builds the optional library fsym_itp (FFTW 3, GPL-2+)
# and its benchmark in build/itp-release (-O3 -march=native -ffp-contract=off) and runs it.
#   bash scripts/itp.sh --quick        about three minutes: sweeps capped (20000 FFTs
#                                      of a 3-D run; norm-decay energy 10000) and stopped at
#                                      1e-10 (norm-decay energy 1e-9), values beyond
#                                      extrapolated (a # line says so); output
#                                      itp_bench_quick.txt, itp_quick.png
#   bash scripts/itp.sh [problem ...]  full sweeps (ho3d pt1d gp3d) to 1e-12; with all three
#                                      problems it draws doc/figures/itp.png
# Prints, per problem and method, `itp problem=NAME method=M order=P ffts_to_1e-8=N
# seconds_to_1e-8=S` (<H>), the same with `itp-norm` (the norm-decay energy), and # lines
# with the sweeps, timing spreads and the CPU (all kept in build/itp-release/itp_bench.txt).
# When every problem ran, it then writes the GP ground state (fsym_itp_run, method A,
# tau = 0.1) to build/itp-release/gp3d.h5 and, with h5py and matplotlib, the figure
# (scripts/plot_itp.py): <H> error against FFTs per method and problem, and the GP
# ground-state density.
set -euo pipefail
cd "$(dirname "$0")/.."
export FSYM_PLOTS=1
source scripts/setup.sh
if ! [ -e /usr/include/fftw3.f03 ]; then
    echo "[itp] FFTW 3 (libfftw3-dev) is missing: run bash scripts/setup.sh as root" >&2
    exit 1
fi
dir=build/itp-release
cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DFSYM_ITP=ON \
    -DCMAKE_Fortran_FLAGS_RELEASE="-O3 -march=native -ffp-contract=off" > /dev/null
cmake --build "$dir" --target fsym_itp_bench fsym_itp_run -j 2 > /dev/null
out=$dir/itp_bench.txt
fig=doc/figures/itp.png
for a in "$@"; do
    # a --quick run keeps its own output and figure; the doc's figure is the full run's
    if [ "$a" = --quick ]; then out=$dir/itp_bench_quick.txt; fig=$dir/itp_quick.png; fi
done
{
    echo "# cpu: $(awk -F': ' '/model name/{print $2; exit}' /proc/cpuinfo), $(nproc) cores"
    "$dir/itp/fsym_itp_bench" "$@"
} | tee "$out"
for a in "$@"; do
    case "$a" in --quick) ;; *) exit 0 ;; esac   # a subset of problems: no figure
done
"$dir/itp/fsym_itp_run" gp3d A 0.1 16 "$dir/gp3d.h5"
if "$FSYM_PYTHON" -c 'import h5py, matplotlib' > /dev/null 2>&1; then
    "$FSYM_PYTHON" scripts/plot_itp.py "$out" "$dir/gp3d.h5" "$fig"
else
    echo "[itp] no h5py/matplotlib: figure not made" >&2
fi
