#!/usr/bin/env bash
# Finds pFUnit (4.x) for the test suite, or builds and caches it. Sourced by scripts/test.sh
# after scripts/setup.sh; sets FSYM_PFUNIT_DIR (the folder of PFUNITConfig.cmake, to pass
# to CMake as PFUNIT_DIR) and says which of these it used, in this order:
#   1. an installed pFUnit that CMake finds by itself (PFUNIT_DIR, CMAKE_PREFIX_PATH, or a
#      system prefix);
#   2. the cached install in $FSYM_PFUNIT_CACHE (default ~/.cache/forward-symplectic/pfunit);
#   3. a build from a source archive or folder: $FSYM_PFUNIT_SOURCE, by default
#      ../shared/vendor/pfunit-4.14.0-src.tar.gz beside the repository when that exists;
#   4. a build from the public repository: git clone --recursive --branch v4.14.0.
# Builds 3 and 4 install into the cache with -j$(nproc), once per machine, and build only what
# the suite uses (the framework's own speed does not matter; it compiles at -O0 anyway):
#   - the serial library: no MPI, OpenMP, fHamcrest or RobustRunner;
#   - assertions for arrays up to rank 2 (MAX_ASSERT_RANK=2; the suite asserts on scalars,
#     vectors and q(d,n));
#   - gFTL-shared's containers (the bulk of the build: some 400 generated modules for every
#     kind of key and element) only for what pFUnit and fArgParse use: elements integer,
#     real, string and unlimited polymorphic, string keys, and (v2) vectors and maps only.
#     scripts/pfunit_trim.py edits the two CMakeLists.txt of gFTL-shared in the unpacked
#     copy; when they are not as expected (another pFUnit version) it changes nothing and
#     the full build runs.
# On a fresh 2-core machine this takes about a minute (148 files) instead of 6-15 (620).
# The cached pFUnit is the suite's own: a project of yours that asserts on arrays of rank 3
# or more needs a pFUnit of its own (PFUNIT_DIR).
set -euo pipefail

fsym_pfunit_say() { printf '[pfunit] %s\n' "$*" >&2; }

# PFUNITConfig.cmake's folder as CMake finds it, with the prefixes given ($1, may be empty);
# empty when not found.
fsym_pfunit_probe() {
    local probe
    probe=$(mktemp -d)
    cat > "$probe/CMakeLists.txt" <<'EOF'
cmake_minimum_required(VERSION 3.16)
project(probe LANGUAGES Fortran)
find_package(PFUNIT QUIET)
if(PFUNIT_FOUND)
    file(WRITE "${CMAKE_BINARY_DIR}/found" "${PFUNIT_DIR}")
endif()
EOF
    cmake -S "$probe" -B "$probe/build" ${1:+-DCMAKE_PREFIX_PATH="$1"} >/dev/null 2>&1 || true
    [ -f "$probe/build/found" ] && cat "$probe/build/found"
    rm -rf "$probe"
}

fsym_pfunit_build() {    # fsym_pfunit_build SOURCE_DIR INSTALL_PREFIX
    local src=$1 prefix=$2 build
    build=$(mktemp -d)
    fsym_pfunit_say "building pFUnit from $src into $prefix (-j$(nproc); once per machine)"
    if declare -F fsym_phase >/dev/null; then fsym_phase "pFUnit build" "$build.log"; fi
    cmake -S "$src" -B "$build" -DCMAKE_INSTALL_PREFIX="$prefix" -DCMAKE_BUILD_TYPE=Release \
        -DSKIP_MPI=YES -DSKIP_OPENMP=YES -DSKIP_FHAMCREST=YES -DSKIP_ROBUST=YES \
        -DENABLE_TESTS=NO -DMAX_ASSERT_RANK=2 > "$build.log" 2>&1 \
        && cmake --build "$build" -j "$(nproc)" >> "$build.log" 2>&1 \
        && cmake --install "$build" >> "$build.log" 2>&1 \
        || { tail -n 40 "$build.log" >&2; fsym_pfunit_say "pFUnit build failed"; return 1; }
    rm -rf "$build" "$build.log"
}

fsym_pfunit_cache=${FSYM_PFUNIT_CACHE:-$HOME/.cache/forward-symplectic/pfunit}
fsym_pfunit_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
FSYM_PFUNIT_DIR=$(fsym_pfunit_probe "")
if [ -n "$FSYM_PFUNIT_DIR" ]; then
    fsym_pfunit_say "installed pFUnit found by CMake: $FSYM_PFUNIT_DIR"
else
    # the cache counts when CMake finds a complete install in it (its targets file checks
    # that the library is there)
    if [ -z "$(fsym_pfunit_probe "$fsym_pfunit_cache")" ]; then
        fsym_pfunit_src=${FSYM_PFUNIT_SOURCE:-}
        if [ -z "$fsym_pfunit_src" ] && \
           [ -f "$fsym_pfunit_root/../shared/vendor/pfunit-4.14.0-src.tar.gz" ]; then
            fsym_pfunit_src=$fsym_pfunit_root/../shared/vendor/pfunit-4.14.0-src.tar.gz
        fi
        fsym_pfunit_tmp=$(mktemp -d)
        if [ -n "$fsym_pfunit_src" ] && [ -d "$fsym_pfunit_src" ]; then
            fsym_pfunit_say "source: the folder $fsym_pfunit_src"
            fsym_pfunit_tree=$fsym_pfunit_src
        elif [ -n "$fsym_pfunit_src" ]; then
            fsym_pfunit_say "source: the archive $(realpath "$fsym_pfunit_src")"
            tar xzf "$fsym_pfunit_src" -C "$fsym_pfunit_tmp"
            fsym_pfunit_tree=$(find "$fsym_pfunit_tmp" -maxdepth 2 -name CMakeLists.txt | head -n 1)
            fsym_pfunit_tree=$(dirname "$fsym_pfunit_tree")
        else
            fsym_pfunit_say "source: git clone --recursive --branch v4.14.0 of pFUnit's repository"
            git clone -q --depth 1 --recursive --shallow-submodules --branch v4.14.0 \
                https://github.com/Goddard-Fortran-Ecosystem/pFUnit.git "$fsym_pfunit_tmp/pFUnit"
            fsym_pfunit_tree=$fsym_pfunit_tmp/pFUnit
        fi
        # a copy of its own that may be trimmed (never the caller's folder)
        if [[ $fsym_pfunit_tree != "$fsym_pfunit_tmp"/* ]]; then
            cp -r "$fsym_pfunit_tree" "$fsym_pfunit_tmp/pFUnit-copy"
            fsym_pfunit_tree=$fsym_pfunit_tmp/pFUnit-copy
        fi
        fsym_pfunit_say "$(python3 "$fsym_pfunit_root/scripts/pfunit_trim.py" "$fsym_pfunit_tree")"
        rm -rf "$fsym_pfunit_cache"
        fsym_pfunit_start=$SECONDS
        fsym_pfunit_build "$fsym_pfunit_tree" "$fsym_pfunit_cache"
        fsym_pfunit_say "built and cached in $((SECONDS - fsym_pfunit_start)) s"
        rm -rf "$fsym_pfunit_tmp"
    else
        fsym_pfunit_say "cached pFUnit: $fsym_pfunit_cache"
    fi
    FSYM_PFUNIT_DIR=$(fsym_pfunit_probe "$fsym_pfunit_cache")
    if [ -z "$FSYM_PFUNIT_DIR" ]; then
        fsym_pfunit_say "CMake does not find pFUnit in $fsym_pfunit_cache"; exit 1
    fi
fi
export FSYM_PFUNIT_DIR
