#!/usr/bin/env bash
# The harness that runs the ORIGINAL SitLog interpreter (Prolog, GPL) from
# a checkout named by $SITLOG_HOME, on one of our applications, through
# driver.pl next to this file. Nothing of the original is copied into this
# repository.
#
# Sourced (tests/conformance/run.sh, legacy_demos.sh, legacy_apps.sh,
# benches/original.sh), it defines:
#
#   original_available
#       prints `skipped: REASON` and returns 1 when the original cannot run
#       (SITLOG_HOME not set, swipl not on PATH, no $SITLOG_HOME/src/init.pl);
#       else makes SITLOG_HOME absolute and exports it.
#   original_prepare APP COPY
#       copies the application APP to COPY with every side file the
#       original opens: a models file listing its *.dm files (sorted) when
#       it has none, basic_actions.pl from $SITLOG_HOME/apps/test_behaviors
#       (so that `screen` and friends print) when it has none, and the other
#       side files empty.
#   original_legacy_setup NAME DEFAULT_TIMEOUT
#       what the scripts that run the original's own apps beside ours
#       (legacy_demos.sh, legacy_apps.sh) share: after original_available,
#       checks python3 and our binary ($SITLOGC, default
#       target/release/sitlogc, set as `sitlogc`), sets `swipl`, `limit`
#       ($CONFORMANCE_TIMEOUT or DEFAULT_TIMEOUT) and `work` (a temporary
#       directory named after NAME, removed on exit unless
#       CONFORMANCE_KEEP=1), and puts in $work/shim a `swipl` that runs
#       `swipl --traditional` (SWI-6 lists, which the original's action code
#       needs). Prints `skipped: REASON` and returns 1 when something is
#       missing.
#   original_run MODE COPY MAIN IN_ARG INPUT OUT LOG TIMEOUT [SWIPL_OPTION...]
#       one run of the original on a prepared COPY (main DM MAIN, initial
#       in_arg IN_ARG, test-mode input from the file INPUT), under `timeout
#       TIMEOUT`; the original's chatter goes to LOG. OUT gets driver.pl's
#       result for MODE (json: a JSON object, count: `TRANSITIONS SECONDS
#       STATUS`); when the run writes none (timeout, crash), OUT says so in
#       the same format.
#
# Run as a command, it runs one application and prints the result:
#
#   tests/conformance/original/original.sh json|count APP [MAIN [IN_ARG]] < INPUT
#
# (MAIN defaults to `main`, IN_ARG to `none`). Environment: ORIGINAL_TIMEOUT
# seconds (default 60), ORIGINAL_STACK_LIMIT (swipl --stack-limit, default
# swipl's own), ORIGINAL_LOG (a file for the original's chatter, default
# discarded). Exit status 0 also when skipped, 2 on usage errors.

original_driver="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/driver.pl"

original_available() {
    if [ -z "${SITLOG_HOME:-}" ]; then
        echo "skipped: SITLOG_HOME not set"
        return 1
    fi
    if ! command -v swipl >/dev/null 2>&1; then
        echo "skipped: swipl not found"
        return 1
    fi
    if [ ! -f "$SITLOG_HOME/src/init.pl" ]; then
        echo "skipped: $SITLOG_HOME/src/init.pl not found (is SITLOG_HOME a checkout of the original?)"
        return 1
    fi
    SITLOG_HOME=$(cd "$SITLOG_HOME" && pwd)
    export SITLOG_HOME
}

original_legacy_setup() {
    local root
    root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
    original_available || return 1
    swipl=$(command -v swipl)
    if ! command -v python3 >/dev/null 2>&1; then
        echo "skipped: python3 not found"
        return 1
    fi
    sitlogc=${SITLOGC:-target/release/sitlogc}
    case "$sitlogc" in
        /*) ;;
        *) sitlogc="$root/$sitlogc" ;;
    esac
    if [ ! -x "$sitlogc" ]; then
        echo "skipped: $sitlogc not built (cargo build --release --bin sitlogc)"
        return 1
    fi
    limit=${CONFORMANCE_TIMEOUT:-$2}
    work=$(mktemp -d "${TMPDIR:-/tmp}/sitlog-$1.XXXXXX")
    if [ "${CONFORMANCE_KEEP:-0}" = 1 ]; then
        echo "work directory: $work"
    else
        trap 'rm -rf "$work"' EXIT
    fi
    mkdir -p "$work/shim"
    printf '#!/bin/sh\nexec %s --traditional "$@"\n' "$swipl" >"$work/shim/swipl"
    chmod +x "$work/shim/swipl"
}

original_prepare() {
    local app=$1 copy=$2 f
    mkdir -p "$copy"
    cp -R "$app/." "$copy/"
    if [ ! -f "$copy/models" ]; then
        (cd "$copy" && find . -name '*.dm' | LC_ALL=C sort | sed "s|^\./||; s|.*|'&'.|") > "$copy/models"
    fi
    if [ ! -f "$copy/basic_actions.pl" ]; then
        # The original's generic basic actions (screen, say, ...), read at
        # run time from the checkout; without them actions are just ignored.
        if [ -f "$SITLOG_HOME/apps/test_behaviors/basic_actions.pl" ]; then
            cp "$SITLOG_HOME/apps/test_behaviors/basic_actions.pl" "$copy/basic_actions.pl"
        else
            : > "$copy/basic_actions.pl"
        fi
    fi
    for f in expectation_types.pl global_vars.pl templates.pl user_functions.pl; do
        [ -f "$copy/$f" ] || : > "$copy/$f"
    done
}

original_run() {
    local mode=$1 copy=$2 main=$3 in_arg=$4 input=$5 out=$6 log=$7 limit=$8 rc
    shift 8
    rm -f "$out"
    (cd "$copy" && timeout "$limit" swipl "$@" -q "$original_driver" \
        "$mode" "$copy" "$main" "$in_arg" models "$out" < "$input" > "$log" 2>&1)
    rc=$?
    [ -s "$out" ] && return 0
    case "$mode" in
        json)
            if [ $rc -eq 124 ]; then
                printf '{"status":"error","error":"original timed out","history":[],"out_arg":null,"globals":{}}\n' > "$out"
            else
                printf '{"status":"error","error":"original crashed (rc %d)","history":[],"out_arg":null,"globals":{}}\n' "$rc" > "$out"
            fi
            ;;
        *)
            if [ $rc -eq 124 ]; then
                echo "0 0 timeout" > "$out"
            else
                echo "0 0 crash(rc=$rc)" > "$out"
            fi
            ;;
    esac
}

if [ "${BASH_SOURCE[0]}" = "$0" ]; then
    set -u
    if [ $# -lt 2 ] || [ $# -gt 4 ] || { [ "$1" != json ] && [ "$1" != count ]; }; then
        echo "usage: $0 json|count APP [MAIN [IN_ARG]] < INPUT" >&2
        exit 2
    fi
    if [ ! -d "$2" ]; then
        echo "error: $2 is not a directory" >&2
        exit 2
    fi
    original_available || exit 0
    work=$(mktemp -d "${TMPDIR:-/tmp}/sitlog-original.XXXXXX")
    trap 'rm -rf "$work"' EXIT
    original_prepare "$2" "$work/app"
    cat > "$work/input"
    stack=()
    [ -z "${ORIGINAL_STACK_LIMIT:-}" ] || stack=(--stack-limit="$ORIGINAL_STACK_LIMIT")
    original_run "$1" "$work/app" "${3:-main}" "${4:-none}" "$work/input" "$work/result" \
        "${ORIGINAL_LOG:-/dev/null}" "${ORIGINAL_TIMEOUT:-60}" "${stack[@]}"
    cat "$work/result"
fi
