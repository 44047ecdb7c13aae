#!/usr/bin/env bash
# The test command: installs what is missing, builds, and runs the whole test suite.
# First the real clients (F77, C, CMake consumer) against the installed library
# (test/clients/run.sh, fails the script on any mismatch), then the Fortran suite, whose
# last line is `N passed, N failed`.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh
bash test/clients/run.sh
fpm test --flag "-std=f2008" "$@"
