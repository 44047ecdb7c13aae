#!/usr/bin/env bash
# The library installed with fpm in the layout of the CMake install, with the same pkg-config
# and CMake package files (fpm itself writes neither):
#   bash scripts/fpm_install.sh PREFIX [FPM OPTIONS...]
#       (default options: --profile release --flag "-ffp-contract=off -frecursive", the
#       flags the CMake build adds)
# gives PREFIX/lib/libfsym.a, the library's modules in PREFIX/include/forward-symplectic (the
# modules of src/ and nothing else: fpm also installs the examples' model modules, which
# are removed again), the C header PREFIX/include/fsym.h, PREFIX/lib/pkgconfig/fsym.pc
# (`pkg-config --cflags --libs fsym`) and PREFIX/lib/cmake/forward-symplectic/ (find_package
# (forward-symplectic), target forward-symplectic::fsym). Both find the prefix from their own
# place, so the tree may be moved. test/clients/run.sh (stage fpm) builds the clients with
# them. Needs fpm on PATH (scripts/setup.sh).
set -euo pipefail
[ $# -ge 1 ] || { echo "usage: bash scripts/fpm_install.sh PREFIX [FPM OPTIONS...]" >&2; exit 2; }
root=$(cd "$(dirname "$0")/.." && pwd)
prefix=$(mkdir -p "$1" && cd "$1" && pwd)
shift
[ $# -gt 0 ] || set -- --profile release --flag "-ffp-contract=off -frecursive"
inc=include/forward-symplectic
version=$(sed -n 's/^version *= *"\(.*\)"/\1/p' "$root/fpm.toml" | head -1)
say() { printf '[fpm-install] %s\n' "$*" >&2; }

(cd "$root" && fpm install "$@" --prefix "$prefix" --includedir "$inc" >&2)
[ -f "$prefix/lib/libfsym.a" ] || { say "fpm install wrote no $prefix/lib/libfsym.a"; exit 1; }
# the library's modules: those src/ defines
lib_modules=$(sed -n 's/^ *[Mm][Oo][Dd][Uu][Ll][Ee]  *\([A-Za-z0-9_]*\) *$/\1/p' "$root"/src/*.f90 \
              | tr 'A-Z' 'a-z' | sort -u)
for m in "$prefix/$inc"/*.mod; do
    name=$(basename "$m" .mod)
    if ! grep -qx "$name" <<< "$lib_modules"; then
        say "removing $name.mod (not a module of the library)"
        rm -f "$m"
    fi
done
install -m 644 "$root/include/fsym.h" "$prefix/include/fsym.h"

mkdir -p "$prefix/lib/pkgconfig"
sed -e 's|@FSYM_PC_PREFIX@|${pcfiledir}/../..|' -e 's|@FSYM_PC_LIBDIR@|${prefix}/lib|' \
    -e 's|@CMAKE_INSTALL_INCLUDEDIR@|include|' -e "s|@PROJECT_VERSION@|$version|" \
    "$root/cmake/fsym.pc.in" > "$prefix/lib/pkgconfig/fsym.pc"

cmakedir=$prefix/lib/cmake/forward-symplectic
mkdir -p "$cmakedir"
cat > "$cmakedir/forward-symplecticConfig.cmake" <<'CMAKE'
# Package configuration of forward-symplectic for an fpm install (written by
# scripts/fpm_install.sh): the imported target forward-symplectic::fsym, as the CMake
# install provides it (the library: integrators, models, F77 layer, C API; it needs neither
# LAPACK nor HDF5 nor MPI).
get_filename_component(_fsym_prefix "${CMAKE_CURRENT_LIST_DIR}/../../.." ABSOLUTE)
if(NOT TARGET forward-symplectic::fsym)
    add_library(forward-symplectic::fsym STATIC IMPORTED)
    set_target_properties(forward-symplectic::fsym PROPERTIES
        IMPORTED_LOCATION "${_fsym_prefix}/lib/libfsym.a"
        IMPORTED_LINK_INTERFACE_LANGUAGES "Fortran"
        INTERFACE_INCLUDE_DIRECTORIES
            "${_fsym_prefix}/include/forward-symplectic;${_fsym_prefix}/include")
endif()
unset(_fsym_prefix)
set(forward-symplectic_FOUND TRUE)
CMAKE
cat > "$cmakedir/forward-symplecticConfigVersion.cmake" <<CMAKE
# Version of the fpm install of forward-symplectic (scripts/fpm_install.sh); compatible
# within the same major version, as the CMake install's SameMajorVersion.
set(PACKAGE_VERSION "$version")
if(PACKAGE_FIND_VERSION VERSION_GREATER PACKAGE_VERSION)
    set(PACKAGE_VERSION_COMPATIBLE FALSE)
elseif(NOT PACKAGE_FIND_VERSION_MAJOR STREQUAL "${version%%.*}")
    set(PACKAGE_VERSION_COMPATIBLE FALSE)
else()
    set(PACKAGE_VERSION_COMPATIBLE TRUE)
    if(PACKAGE_FIND_VERSION STREQUAL PACKAGE_VERSION)
        set(PACKAGE_VERSION_EXACT TRUE)
    endif()
endif()
CMAKE
say "installed into $prefix: lib/libfsym.a, $(ls "$prefix/$inc"/*.mod | wc -l) modules, include/fsym.h, lib/pkgconfig/fsym.pc, lib/cmake/forward-symplectic/"
