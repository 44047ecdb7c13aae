#!/usr/bin/env bash
# Proof by real clients: build and install the core library with CMake into a temporary
# prefix, then build against the INSTALLED library
#   - Makefile style: the F77 client with `gfortran ... -lfsym` alone (no HDF5, no LAPACK),
#     the C client with `pkg-config --libs --static fsym`, the modern reference with `use fsym`;
#   - CMake style: the same three through find_package(forward-symplectic);
#   - fpm style: the same three against `fpm install` (when fpm is on PATH);
# run them all and check that every client reproduces the modern API bit for bit.
# Exits non-zero on any failure. Run from anywhere; FSYM_KEEP=1 keeps the temporary tree.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
tmp=$(mktemp -d)
if [ "${FSYM_KEEP:-0}" != 1 ]; then trap 'rm -rf "$tmp"' EXIT; fi
say() { printf '[clients] %s\n' "$*"; }
quiet() { "$@" > "$tmp/log" 2>&1 || { cat "$tmp/log"; return 1; }; }

prefix=$tmp/prefix
say "CMake build and install of libfsym into $prefix"
quiet cmake -S "$root" -B "$tmp/lib" -DCMAKE_INSTALL_PREFIX="$prefix" -DCMAKE_BUILD_TYPE=Release
quiet cmake --build "$tmp/lib" -j 2
quiet cmake --install "$tmp/lib"

mk=$tmp/make; mkdir -p "$mk"
say "gfortran f77_nbody.f -L$prefix/lib -lfsym   (nothing else)"
gfortran -O2 -ffp-contract=off "$here/f77_nbody.f" -L"$prefix/lib" -lfsym -o "$mk/f77_nbody"
if nm "$mk/f77_nbody" | grep -qiE 'h5[a-z]*_|dgeev|dgesv'; then say "HDF5/LAPACK symbols linked"; exit 1; fi
export PKG_CONFIG_PATH="$prefix/lib/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
say "cc c_nbody.c \$(pkg-config --cflags --libs --static fsym)  -> $(pkg-config --libs --static fsym)"
cc -O2 -ffp-contract=off "$here/c_nbody.c" $(pkg-config --cflags --libs --static fsym) -o "$mk/c_nbody"
gfortran -O2 -ffp-contract=off -I"$prefix/include/forward-symplectic" "$here/modern_nbody.f90" \
    -L"$prefix/lib" -lfsym -o "$mk/modern_nbody"

say "CMake consumer: find_package(forward-symplectic), target forward-symplectic::fsym"
quiet cmake -S "$here/cmake_consumer" -B "$tmp/consumer" -DCMAKE_PREFIX_PATH="$prefix"
quiet cmake --build "$tmp/consumer" -j 2

dirs=("$mk" "$tmp/consumer")
if command -v fpm >/dev/null 2>&1; then
    say "fpm install --prefix $tmp/fpm-prefix; clients linked with -lforward-symplectic"
    fp=$tmp/fpm; mkdir -p "$fp"
    (cd "$root" && quiet fpm install --profile release --flag "-ffp-contract=off" \
        --prefix "$tmp/fpm-prefix")
    gfortran -O2 -ffp-contract=off "$here/f77_nbody.f" -L"$tmp/fpm-prefix/lib" \
        -lforward-symplectic -o "$fp/f77_nbody"
    cc -O2 -ffp-contract=off -I"$root/include" "$here/c_nbody.c" -L"$tmp/fpm-prefix/lib" \
        -lforward-symplectic -lgfortran -lm -o "$fp/c_nbody"
    gfortran -O2 -ffp-contract=off -I"$tmp/fpm-prefix/include" "$here/modern_nbody.f90" \
        -L"$tmp/fpm-prefix/lib" -lforward-symplectic -o "$fp/modern_nbody"
    dirs+=("$fp")
fi

status=0
for dir in "${dirs[@]}"; do
    "$dir/modern_nbody" > "$dir/modern.txt"
    "$dir/f77_nbody" > "$dir/f77.txt"
    "$dir/c_nbody" > "$dir/c.txt"
    grep -h -E '^(short|unknown)' "$dir/f77.txt" "$dir/c.txt" | sed 's/^/[clients]   /'
    say "$(basename "$dir"): comparing with the modern API"
    (cd "$dir" && python3 "$here/compare.py" modern.txt f77.txt c.txt) | sed 's/^/[clients]   /' \
        || status=1
done
# the two builds (Makefile style and CMake) agree with each other too
cmp -s "$mk/modern.txt" "$tmp/consumer/modern.txt" || { say "Make and CMake builds differ"; status=1; }
if [ $status -ne 0 ]; then say "FAILED"; exit 1; fi
say "all clients reproduce the modern API bit for bit"
