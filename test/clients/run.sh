#!/usr/bin/env bash
# Proof by real clients, against the INSTALLED library. CTest runs it stage by stage (see
# test/CMakeLists.txt); without arguments it runs every stage in a temporary folder.
#
#   run.sh install DIR [TREE]
#                           CMake build and install of the core library into DIR/prefix; with
#                           TREE (a configured and built CMake tree of this project, as CTest
#                           passes its own), `cmake --install TREE --prefix DIR/prefix` alone
#   run.sh modern DIR       the modern reference client (`use fsym`), Makefile style
#   run.sh f77 DIR          the F77 client with `gfortran ... -lfsym` alone (no HDF5, no
#                           LAPACK), compared with the modern client bit for bit
#   run.sh c DIR            the C client with `pkg-config --libs --static fsym`, compared
#   run.sh cmake DIR        the three through find_package(forward-symplectic), compared with
#                           each other and with the Makefile-style modern client
#   run.sh fpm DIR          the three against `bash scripts/fpm_install.sh` (fpm install plus
#                           the pkg-config and CMake files; exit 77, skipped, without fpm):
#                           the same modules as the CMake install, the C client through its
#                           fsym.pc, the three again through its find_package
#   run.sh example DIR [PFUNIT_DIR]
#                           example/user_model_test: a user's model tested with pFUnit,
#                           built with CMake against DIR/prefix, run by its own CTest
#
# Every stage after `install` needs DIR/prefix. Exits non-zero on any failure.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
say() { printf '[clients] %s\n' "$*"; }
quiet() { "$@" > "$work/log" 2>&1 || { cat "$work/log"; return 1; }; }
fflags=(-O2 -ffp-contract=off)

stage_install() {
    if [ -n "${1:-}" ]; then
        say "cmake --install $1 --prefix $prefix (the library of this tree)"
        quiet cmake --install "$1" --prefix "$prefix"
        return
    fi
    say "CMake build and install of libfsym into $prefix"
    quiet cmake -S "$root" -B "$dir/lib" -DCMAKE_INSTALL_PREFIX="$prefix" \
        -DCMAKE_BUILD_TYPE=Release
    quiet cmake --build "$dir/lib" -j "$(nproc)"
    quiet cmake --install "$dir/lib"
}

need_prefix() {
    [ -f "$prefix/lib/pkgconfig/fsym.pc" ] || { say "no installed library in $prefix"; exit 1; }
}

build_modern() {   # build_modern OUTDIR
    gfortran "${fflags[@]}" -I"$prefix/include/forward-symplectic" "$here/modern_nbody.f90" \
        -L"$prefix/lib" -lfsym -J "$1" -o "$1/modern_nbody"
    "$1/modern_nbody" > "$1/modern.txt"
}

compare() {        # compare OUTDIR CLIENT...: each CLIENT.txt against modern.txt
    local out=$1; shift
    local files=()
    for c in "$@"; do files+=("$c.txt"); done
    grep -h -E '^(short|unknown)' "${files[@]/#/$out/}" | sed 's/^/[clients]   /' || true
    say "$(basename "$out"): $* against the modern API"
    (cd "$out" && python3 "$here/compare.py" modern.txt "${files[@]}") | sed 's/^/[clients]   /'
    return "${PIPESTATUS[0]}"
}

stage_modern() {
    need_prefix; mkdir -p "$work"
    build_modern "$work"
    say "modern reference: $(wc -l < "$work/modern.txt") lines"
}

stage_f77() {
    need_prefix; mkdir -p "$work"
    build_modern "$work"
    say "gfortran f77_nbody.f -L$prefix/lib -lfsym   (nothing else)"
    gfortran "${fflags[@]}" "$here/f77_nbody.f" -L"$prefix/lib" -lfsym -o "$work/f77_nbody"
    if grep -qiE 'h5[a-z]*_|dgeev|dgesv' <<< "$(nm "$work/f77_nbody")"; then
        say "HDF5/LAPACK symbols linked"; exit 1
    fi
    "$work/f77_nbody" > "$work/f77.txt"
    compare "$work" f77
}

stage_c() {
    need_prefix; mkdir -p "$work"
    build_modern "$work"
    export PKG_CONFIG_PATH="$prefix/lib/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
    local libs
    libs=$(pkg-config --cflags --libs --static fsym)
    say "cc c_nbody.c \$(pkg-config --cflags --libs --static fsym)  -> $libs"
    # shellcheck disable=SC2086
    cc -O2 -ffp-contract=off "$here/c_nbody.c" $libs -o "$work/c_nbody"
    "$work/c_nbody" > "$work/c.txt"
    compare "$work" c
}

stage_cmake() {
    need_prefix; mkdir -p "$work/make"
    say "CMake consumer: find_package(forward-symplectic), target forward-symplectic::fsym"
    quiet cmake -S "$here/cmake_consumer" -B "$work" -DCMAKE_PREFIX_PATH="$prefix"
    quiet cmake --build "$work" -j "$(nproc)"
    "$work/modern_nbody" > "$work/modern.txt"
    "$work/f77_nbody" > "$work/f77.txt"
    "$work/c_nbody" > "$work/c.txt"
    compare "$work" f77 c
    build_modern "$work/make"
    cmp -s "$work/make/modern.txt" "$work/modern.txt" \
        || { say "Makefile-style and CMake builds differ"; exit 1; }
    say "Makefile-style and CMake builds agree"
}

stage_fpm() {
    command -v fpm >/dev/null 2>&1 || { say "fpm not on PATH: skipped"; exit 77; }
    need_prefix; mkdir -p "$work"
    local p=$work/prefix inc=include/forward-symplectic
    say "bash scripts/fpm_install.sh $p: fpm install in the CMake layout, with fsym.pc and"
    say "  the CMake package files"
    # the flags of fpm_consumer/check.sh: both then use one build of this package
    quiet bash "$root/scripts/fpm_install.sh" "$p" --flag "${fflags[*]}"
    [ -f "$p/lib/libfsym.a" ] || { say "fpm install gave no lib/libfsym.a"; exit 1; }
    # the same modules as the CMake install (the library's, fsym_checks among them), no more
    local m missing=() extra=()
    for m in "$prefix/$inc"/*.mod; do
        [ -f "$p/$inc/$(basename "$m")" ] || missing+=("$(basename "$m")")
    done
    for m in "$p/$inc"/*.mod; do
        [ -f "$prefix/$inc/$(basename "$m")" ] || extra+=("$(basename "$m")")
    done
    if [ ${#missing[@]} -gt 0 ] || [ ${#extra[@]} -gt 0 ]; then
        say "fpm and CMake installs differ: only CMake: ${missing[*]:-none}; only fpm: \
${extra[*]:-none}"; exit 1
    fi
    say "fpm install has the modules of the CMake install, no more ($(ls "$p/$inc"/*.mod | wc -l))"
    [ -f "$p/include/fsym.h" ] || { say "no include/fsym.h in the fpm install"; exit 1; }
    gfortran "${fflags[@]}" "$here/f77_nbody.f" -L"$p/lib" -lfsym \
        -o "$work/f77_nbody"
    local libs
    libs=$(PKG_CONFIG_PATH="$p/lib/pkgconfig" pkg-config --cflags --libs --static fsym)
    say "cc c_nbody.c \$(pkg-config --cflags --libs --static fsym) of the fpm install"
    # shellcheck disable=SC2086
    cc -O2 -ffp-contract=off "$here/c_nbody.c" $libs -o "$work/c_nbody"
    gfortran "${fflags[@]}" -I"$p/$inc" "$here/modern_nbody.f90" -L"$p/lib" \
        -lfsym -J "$work" -o "$work/modern_nbody"
    "$work/modern_nbody" > "$work/modern.txt"
    "$work/f77_nbody" > "$work/f77.txt"
    "$work/c_nbody" > "$work/c.txt"
    compare "$work" f77 c
    say "CMake consumer against the fpm install: find_package(forward-symplectic)"
    mkdir -p "$work/cmake"
    quiet cmake -S "$here/cmake_consumer" -B "$work/cmake" -DCMAKE_PREFIX_PATH="$p"
    quiet cmake --build "$work/cmake" -j "$(nproc)"
    local c
    for c in modern f77 c; do "$work/cmake/${c}_nbody" > "$work/cmake/$c.txt"; done
    compare "$work/cmake" f77 c
    cmp -s "$work/cmake/modern.txt" "$work/modern.txt" \
        || { say "CMake consumer and direct builds against the fpm install differ"; exit 1; }
}

stage_example() {
    need_prefix; mkdir -p "$work"
    local pf=${1:-}
    local path="$prefix"
    [ -n "$pf" ] && path="$prefix;$pf"
    say "example/user_model_test: pFUnit test of a user's model against the installed library"
    quiet cmake -S "$root/example/user_model_test" -B "$work" -DCMAKE_PREFIX_PATH="$path" \
        ${pf:+-DPFUNIT_DIR="$pf"}
    quiet cmake --build "$work" -j "$(nproc)"
    (cd "$work" && ctest --output-on-failure) | sed 's/^/[clients]   /'
    return "${PIPESTATUS[0]}"
}

if [ $# -eq 0 ]; then
    dir=$(mktemp -d)
    if [ "${FSYM_KEEP:-0}" != 1 ]; then trap 'rm -rf "$dir"' EXIT; fi
    for s in install modern f77 c cmake fpm; do
        rc=0
        bash "$0" "$s" "$dir" || rc=$?
        if [ $rc -ne 0 ] && [ $rc -ne 77 ]; then say "FAILED ($s)"; exit 1; fi
    done
    say "all clients reproduce the modern API bit for bit"
    exit 0
fi

stage=$1
dir=$(mkdir -p "$2" && cd "$2" && pwd)
prefix=$dir/prefix
work=$dir/$stage
case "$stage" in
    install) work=$dir; stage_install "${3:-}" ;;
    modern | f77 | c | cmake | fpm) "stage_$stage" ;;
    example) stage_example "${3:-}" ;;
    *) echo "run.sh: unknown stage $stage" >&2; exit 2 ;;
esac
