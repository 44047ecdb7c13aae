#!/usr/bin/env bash
# Build every example with -std=f2008, run it, and store its output in doc/output/<name>.txt
# (the documentation pages include these files). Run from the project root:
#     bash scripts/examples.sh
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p doc/output
fpm build --flag "-std=f2008 -ffp-contract=off"
for src in example/fsym_example_*.f90; do
    name=$(basename "$src" .f90)
    echo "== $name"
    fpm run --flag "-std=f2008 -ffp-contract=off" --example "$name" > "doc/output/$name.txt"
    cat "doc/output/$name.txt"
done
