#!/usr/bin/env bash
# The programs of app/ (the fpm package fsym-apps, app/fpm.toml), for the scripts: sourced
# by every script that runs one (after scripts/setup.sh, which puts fpm on PATH).
#   fsym_app PROGRAM [FPM OPTIONS...] [-- ARGS...]   (or, as a command: bash scripts/apps.sh ...)
#       builds app/ with the fpm options (e.g. --profile release --flag "-O3 ...") and runs
#       PROGRAM with ARGS in the caller's directory (relative paths stay the caller's)
#   fsym_app_exe PROGRAM [FPM OPTIONS...]
#       builds app/ and prints the absolute path of PROGRAM's executable
# fpm's own messages go to stderr, so the program's standard output is the caller's.
# By hand: cd app && fpm run --profile release fsym-study -- --list
fsym_app_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")/../app" && pwd)

fsym_app_exe() {
    local name=$1 rel
    shift
    (cd "$fsym_app_dir" && fpm build "$@" >&2) || return 1
    rel=$(cd "$fsym_app_dir" && fpm run "$@" --runner echo "$name" 2>/dev/null | tail -n 1) \
        || return 1
    [ -n "$rel" ] && [ -x "$fsym_app_dir/$rel" ] || {
        printf '[apps] no executable %s in app/ (fpm run --runner echo said "%s")\n' \
            "$name" "$rel" >&2
        return 1
    }
    printf '%s/%s\n' "$fsym_app_dir" "$rel"
}

fsym_app() {
    local name=$1 exe
    shift
    local opts=()
    while [ $# -gt 0 ] && [ "$1" != "--" ]; do opts+=("$1"); shift; done
    [ $# -gt 0 ] && shift
    exe=$(fsym_app_exe "$name" "${opts[@]}") || return 1
    "$exe" "$@"
}

# Run as a command (not sourced): bash scripts/apps.sh PROGRAM [FPM OPTIONS...] [-- ARGS...]
if [ "${BASH_SOURCE[0]}" = "$0" ]; then
    set -euo pipefail
    [ $# -ge 1 ] || { echo "usage: bash scripts/apps.sh PROGRAM [FPM OPTIONS...] [-- ARGS...]" >&2; exit 2; }
    fsym_app "$@"
fi
