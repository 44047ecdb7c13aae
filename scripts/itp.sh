#!/usr/bin/env bash
# Imaginary-time benchmark (issue 26): builds the optional library fsym_itp (FFTW 3, GPL-2+)
# and its benchmark in build/itp-release (-O3 -march=native -ffp-contract=off) and runs it.
#   bash scripts/itp.sh --quick        a minute or two: sweeps capped (40000 FFTs of a 3-D
#                                      run), values beyond the cap extrapolated (a # line says so)
#   bash scripts/itp.sh [problem ...]  full sweeps (ho3d pt1d gp3d)
# Prints, per problem and method, `itp problem=NAME method=M order=P ffts_to_1e-8=N
# seconds_to_1e-8=S` and # lines with the sweeps, timing spreads and the CPU.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh
if ! [ -e /usr/include/fftw3.f03 ]; then
    echo "[itp] FFTW 3 (libfftw3-dev) is missing: run bash scripts/setup.sh as root" >&2
    exit 1
fi
dir=build/itp-release
cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DFSYM_ITP=ON \
    -DCMAKE_Fortran_FLAGS_RELEASE="-O3 -march=native -ffp-contract=off" > /dev/null
cmake --build "$dir" --target fsym_itp_bench -j 2 > /dev/null
echo "# cpu: $(awk -F': ' '/model name/{print $2; exit}' /proc/cpuinfo), $(nproc) cores"
"$dir/itp/fsym_itp_bench" "$@"
