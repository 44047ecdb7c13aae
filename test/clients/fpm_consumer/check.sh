#!/usr/bin/env bash
# Proof that a project using forward-symplectic through fpm links neither LAPACK nor HDF5:
# copies this consumer to a temporary directory (path dependency rewritten to this checkout),
# builds it with `fpm build --verbose`, runs it, and checks
#   1. the consumer's link line names no -llapack, -lblas, -lhdf5* (fpm passes a dependency's
#      [build] link on to its consumers, so the library must declare none);
#   2. `nm` of the executable has no LAPACK or HDF5 symbol, and `ldd` lists no such library;
#   3. as a control that the check can fail: `nm` of the programs' package (app/, fsym-apps)
#      finds LAPACK in fsym-stability (the program that needs it), and in fsym-solar, built
#      from the same package (and linking HDF5, which it uses), neither LAPACK (nm, ldd) nor
#      the study module that calls it (each program takes only the app/ modules it uses).
# Exits non-zero on any failure. Run from anywhere; needs fpm on PATH.
set -euo pipefail
# (nm and ldd output is captured before grep -q reads it: grep -q stops at the first match,
# the writer then dies of SIGPIPE, and pipefail would turn a found symbol into a miss)
command -v fpm > /dev/null 2>&1 || { echo "[fpm-consumer] fpm not on PATH: skipped"; exit 77; }
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
say() { printf '[fpm-consumer] %s\n' "$*"; }
flags="-O2 -ffp-contract=off"
bad='-l(lapack|blas|hdf5[a-z_]*)\b'

cp -r "$here/." "$tmp/consumer"
rm -rf "$tmp/consumer/build"
rel=$(python3 -c 'import os,sys; print(os.path.relpath(sys.argv[1], sys.argv[2]))' "$root" "$tmp/consumer")
sed -i "s|path = \"../../..\"|path = \"$rel\"|" "$tmp/consumer/fpm.toml"
cd "$tmp/consumer"
fpm build --flag "$flags" --verbose > "$tmp/build.log" 2>&1 || { cat "$tmp/build.log"; exit 1; }
exe=$(fpm run --flag "$flags" --runner echo 2>/dev/null | tail -1)
link=$(grep -E -- "-o [^ ]*app/fsym-fpm-consumer( |$)" "$tmp/build.log" | tail -1)
[ -n "$link" ] || { say "consumer link line not found"; cat "$tmp/build.log"; exit 1; }
say "link line: ...${link##*-Werror=implicit-interface}"
status=0
if grep -qE -- "$bad" <<< "$link"; then say "FAIL: the consumer links LAPACK or HDF5"; status=1
else say "link line names neither LAPACK/BLAS nor HDF5"; fi
if grep -qiE ' [TUu] (dgeev|dsyev|dgemm)_?$|h5[a-z]*_' <<< "$(nm "$exe")"; then
    say "FAIL: LAPACK or HDF5 symbols in the executable"; status=1
else say "nm: no LAPACK or HDF5 symbol in the executable"; fi
if grep -qiE 'liblapack|libblas|libhdf5' <<< "$(ldd "$exe")"; then
    say "FAIL: ldd lists LAPACK or HDF5"; status=1
else say "ldd: $(ldd "$exe" | awk '{print $1}' | tr '\n' ' ')"; fi
"$exe" | sed 's/^/[fpm-consumer]   /' || { say "FAIL: the consumer did not run"; status=1; }

# The other dependency lines of the README: a git dependency (here the URL of this checkout,
# pinned to its commit, as a user's line names the public repository) gives the same program
# output; an absolute path is refused by fpm 0.12 with "could not be found" (its own
# limitation; the README says so and gives the relative path or git as the way): the check
# fails if fpm refuses it in any other way, and says so when a later fpm accepts it.
first=$("$exe")
if git -C "$root" rev-parse HEAD > /dev/null 2>&1; then
    rev=$(git -C "$root" rev-parse HEAD)
    cp -r "$here/." "$tmp/consumer_git"
    rm -rf "$tmp/consumer_git/build"
    sed -i "s|path = \"../../..\"|git = \"file://$root\", rev = \"$rev\"|" \
        "$tmp/consumer_git/fpm.toml"
    grep -q "rev = \"$rev\"" "$tmp/consumer_git/fpm.toml" || { say "FAIL: git line not set"; exit 1; }
    (cd "$tmp/consumer_git" && fpm build --flag "$flags" > "$tmp/git.log" 2>&1) \
        || { cat "$tmp/git.log"; say "FAIL: git dependency did not build"; status=1; }
    gexe=$(cd "$tmp/consumer_git" && fpm run --flag "$flags" --runner echo 2>/dev/null | tail -1)
    if [ "$(cd "$tmp/consumer_git" && "$gexe")" = "$first" ]; then say "git dependency (file://..., rev = $rev): same output"
    else say "FAIL: the git dependency's program prints something else"; status=1; fi
else
    say "not a git checkout: git dependency not tried"
fi
cp -r "$here/." "$tmp/consumer_abs"
rm -rf "$tmp/consumer_abs/build"
sed -i "s|path = \"../../..\"|path = \"$root\"|" "$tmp/consumer_abs/fpm.toml"
if (cd "$tmp/consumer_abs" && fpm build --flag "$flags" > "$tmp/abs.log" 2>&1); then
    say "absolute path dependency accepted by this fpm ($(fpm --version | awk '/Version/{print $2}'))"
elif grep -q "could not be found" "$tmp/abs.log"; then
    say "absolute path dependency refused by fpm as the README says (use a relative path or git)"
else
    cat "$tmp/abs.log"; say "FAIL: absolute path dependency failed otherwise"; status=1
fi

# Control: the same checks detect LAPACK where it is linked, and per-program pruning of the
# programs' package app/ (fsym-apps: its [build] link names LAPACK for every program, after
# its library archive, and each program takes from that archive only the modules it uses).
cd "$root/app"
fpm build --flag "$flags" > "$tmp/self.log" 2>&1 || { cat "$tmp/self.log"; exit 1; }
stab=$(fpm run --flag "$flags" --runner echo fsym-stability 2>/dev/null | tail -1)
solar=$(fpm run --flag "$flags" --runner echo fsym-solar 2>/dev/null | tail -1)
lapack_syms='^ +U (dsyev|dgeev)_?$'
if grep -qE "$lapack_syms" <<< "$(nm "$stab")"; then say "control: fsym-stability calls LAPACK (detected)"
else say "FAIL: control: no LAPACK symbol found in fsym-stability ($stab)"; status=1; fi
if grep -qE "$lapack_syms|fsym_linear_stability" <<< "$(nm "$solar")" \
    || grep -qE 'lib(lapack|blas)' <<< "$(ldd "$solar")"; then
    say "FAIL: control: fsym-solar links LAPACK or the LAPACK study module"; status=1
else say "control: fsym-solar has neither LAPACK nor app/study/fsym_linear_stability.f90 (pruned)"; fi
[ $status -eq 0 ] && say "the fpm consumer links neither LAPACK nor HDF5"
exit $status
