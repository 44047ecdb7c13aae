#!/usr/bin/env bash
# Installs what forward-symplectic needs, when it is missing, and puts fpm on PATH.
# Sourced by scripts/main.sh and scripts/test.sh; safe to run again.
#   FSYM_PLOTS=1  also install the Python plotting stack (matplotlib, h5py, numpy)
#   FSYM_VENV     where the Python virtual environment lives (default ~/.cache/forward-symplectic/venv)
set -euo pipefail

fsym_say() { printf '[setup] %s\n' "$*" >&2; }

missing=()
command -v gfortran >/dev/null 2>&1 || missing+=(gfortran)
command -v pkg-config >/dev/null 2>&1 || missing+=(pkg-config)
pkg-config --exists hdf5 2>/dev/null && [ -e /usr/include/hdf5/serial/hdf5.mod ] || missing+=(libhdf5-dev)
ls /usr/lib/*/liblapack.so >/dev/null 2>&1 || ls /usr/lib/liblapack.so >/dev/null 2>&1 || missing+=(liblapack-dev)
ls /usr/lib/*/libblas.so >/dev/null 2>&1 || ls /usr/lib/libblas.so >/dev/null 2>&1 || missing+=(libblas-dev)
command -v cmake >/dev/null 2>&1 || missing+=(cmake)
command -v make >/dev/null 2>&1 || missing+=(make)
# --- test suite (issue 12): pFUnit's build needs m4; the C client needs a C compiler; without
# a pFUnit source archive, scripts/pfunit.sh clones pFUnit with git ---
command -v m4 >/dev/null 2>&1 || missing+=(m4)
command -v cc >/dev/null 2>&1 || missing+=(gcc)
fsym_vendor=$(dirname "${BASH_SOURCE[0]}")/../../shared/vendor
if [ -z "${FSYM_PFUNIT_SOURCE:-}" ] && [ ! -f "$fsym_vendor/pfunit-4.14.0-src.tar.gz" ]; then
    command -v git >/dev/null 2>&1 || missing+=(git)
fi
# issue 26: the optional imaginary-time library (itp/, built by the test command's release
# tree) needs FFTW 3 with its Fortran 2003 interface (GPL-2+; the core library does not use it)
[ -e /usr/include/fftw3.f03 ] && pkg-config --exists fftw3 2>/dev/null || missing+=(libfftw3-dev)
# --- end of the test-suite block ---

# ---- begin issue 14: OpenMPI, only when the MPI parts are built (FSYM_MPI=1; scripts/scale.sh
# sets it): Debian's libopenmpi-dev (mpif90 and the mpi_f08 module) and openmpi-bin (mpirun).
if [ "${FSYM_MPI:-0}" = 1 ]; then
    command -v mpif90 >/dev/null 2>&1 || missing+=(libopenmpi-dev)
    command -v mpirun >/dev/null 2>&1 || missing+=(openmpi-bin)
    fsym_say "MPI parts requested: they need libopenmpi-dev and openmpi-bin (OpenMPI)"
fi
# ---- end issue 14 ----

if [ ${#missing[@]} -gt 0 ]; then
    if [ "$(id -u)" -eq 0 ]; then SUDO=""; elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then SUDO="sudo"; else
        fsym_say "missing system packages: ${missing[*]}"
        fsym_say "install them (Debian/Ubuntu: apt-get install ${missing[*]}) and run this again"
        exit 1
    fi
    fsym_say "installing ${missing[*]} with apt-get"
    export DEBIAN_FRONTEND=noninteractive
    $SUDO apt-get update -qq
    $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

venv=${FSYM_VENV:-$HOME/.cache/forward-symplectic/venv}
pkgs=()
if ! command -v fpm >/dev/null 2>&1 && [ ! -x "$venv/bin/fpm" ]; then pkgs+=(fpm); fi
if [ "${FSYM_PLOTS:-0}" = 1 ] && ! python3 -c 'import matplotlib, h5py, numpy' >/dev/null 2>&1 \
    && ! { [ -x "$venv/bin/python" ] && "$venv/bin/python" -c 'import matplotlib, h5py, numpy' >/dev/null 2>&1; }; then
    pkgs+=(matplotlib h5py numpy)
fi
if [ ${#pkgs[@]} -gt 0 ]; then
    if [ ! -x "$venv/bin/pip" ]; then
        fsym_say "creating a Python virtual environment in $venv"
        python3 -m venv "$venv"
    fi
    fsym_say "pip install ${pkgs[*]}"
    "$venv/bin/pip" install -q "${pkgs[@]}"
fi
if [ -d "$venv/bin" ]; then export PATH="$PATH:$venv/bin"; fi
if [ -x "$venv/bin/python" ] && "$venv/bin/python" -c 'import matplotlib, h5py' >/dev/null 2>&1; then
    export FSYM_PYTHON="$venv/bin/python"
else
    export FSYM_PYTHON=python3
fi
command -v fpm >/dev/null 2>&1 || { fsym_say "fpm still not found"; exit 1; }
fsym_say "gfortran $(gfortran -dumpversion), fpm $(fpm --version 2>/dev/null | awk '/Version/{sub(/,$/, "", $2); print $2}')"
