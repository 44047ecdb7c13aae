#!/usr/bin/env bash
# Progress lines for the test command (sourced by scripts/test.sh; scripts/pfunit.sh uses
# fsym_phase when it is defined). `fsym_phase NAME [LOG...]` says which phase runs and which
# logs show how far it is; a background heartbeat prints, every $FSYM_HEARTBEAT seconds
# (default 30), a line such as
#   [test] 3:30 build: debug 57% (build/test-debug.log), release 80% (build/test-release.log)
# with the last make percentage of each log, or the number of tests done for a CTest log.
# `fsym_phases_summary` prints the time each phase took; `fsym_heartbeat_stop` ends it.
fsym_t0=$(date +%s)
fsym_progress_file=$(mktemp)
fsym_phase_times=()
fsym_phase_name=""
fsym_phase_start=$fsym_t0

fsym_clock() {   # m:ss since the start
    local s=$(( $(date +%s) - fsym_t0 ))
    printf '%d:%02d' $((s / 60)) $((s % 60))
}

fsym_phase_end() {   # closes the current phase (its time goes to the summary)
    local now
    now=$(date +%s)
    if [ -n "$fsym_phase_name" ]; then
        fsym_phase_times+=("$fsym_phase_name|$((now - fsym_phase_start))")
    fi
    fsym_phase_name=""
    fsym_phase_start=$now
}

fsym_phase() {   # fsym_phase NAME [LOG...]
    fsym_phase_end
    fsym_phase_name=$1
    printf '%s\n' "$@" > "$fsym_progress_file"
    printf '[test] %s phase: %s\n' "$(fsym_clock)" "$1" >&2
}

fsym_progress_of() {   # how far a log is: make's last percentage or CTest's tests done
    local log=$1 done pct
    [ -s "$log" ] || { printf 'starting'; return; }
    done=$(grep -oE '^ *[0-9]+/[0-9]+ Test +#' "$log" | tail -n 1 | tr -d ' ' | cut -d T -f 1)
    if [ -n "$done" ]; then printf '%s tests' "$done"; return; fi
    pct=$(grep -oE '^\[ *[0-9]+%\]' "$log" | tail -n 1 | tr -d '[] ')
    if [ -n "$pct" ]; then printf '%s' "$pct"; else printf '%s lines' "$(wc -l < "$log")"; fi
}

fsym_heartbeat_line() {
    local name log parts=()
    { read -r name; while read -r log; do
        parts+=("$(basename "${log%.log}") $(fsym_progress_of "$log")")
    done; } < "$fsym_progress_file"
    local text=""
    if [ ${#parts[@]} -gt 0 ]; then
        text=": ${parts[0]}"
        for log in "${parts[@]:1}"; do text+=", $log"; done
    fi
    printf '[test] %s %s%s\n' "$(fsym_clock)" "${name:-starting}" "$text" >&2
}

fsym_heartbeat_start() {
    (
        set +e   # a failed read or grep must not end the heartbeat
        trap 'exit 0' TERM
        while sleep "${FSYM_HEARTBEAT:-30}"; do fsym_heartbeat_line; done
    ) &
    fsym_heartbeat_pid=$!
}

fsym_heartbeat_stop() {
    if [ -n "${fsym_heartbeat_pid:-}" ]; then
        kill "$fsym_heartbeat_pid" 2>/dev/null || true
        wait "$fsym_heartbeat_pid" 2>/dev/null || true
        fsym_heartbeat_pid=""
    fi
    rm -f "$fsym_progress_file"
}

fsym_phases_summary() {   # one line: each phase and its time, then the total
    local item out=""
    fsym_phase_end
    for item in "${fsym_phase_times[@]}"; do
        out+="${item%%|*} ${item##*|} s, "
    done
    printf '[test] phases: %stotal %s s\n' "$out" "$(( $(date +%s) - fsym_t0 ))" >&2
}
