#!/usr/bin/env bash
# Runs each first-week program of cli/tests/hunt/ (issue 39) through the
# ORIGINAL SitLog interpreter in test mode and compares how its run ends
# with the `original:` line of the program's `expect` file: `ok` (the run
# reaches a final situation of the main DM) or `stops` (an error, or no end
# before its input runs out or the time limit). What `sitlogc check` and
# `sitlogc run` do with the same programs is tested by cli/tests/cli/hunt.rs;
# docs/guide/checking.md has the table. Nothing of the original is kept here.
#
# Environment:
#   SITLOG_HOME          the original's tree (required, else skip)
#   swipl                SWI-Prolog on PATH (required, else skip); run as
#                        `swipl --traditional` (SWI-6 lists, which the
#                        original's action code needs)
#   CONFORMANCE_TIMEOUT  seconds per run (default 15; a program the
#                        original loops on takes that long)
#   CONFORMANCE_KEEP=1   keep the work directory and print its path
#
# Usage: tests/conformance/hunt.sh [PROGRAM_DIR...]  (default: all)
# Output: one line per program, `NAME: ok` / `NAME: stops`, and
# `(expected ...)` where it differs. Exit status 0 when all agree (or
# skipped), 1 otherwise.
set -u

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)

# shellcheck source=original/original.sh
. "$here/original/original.sh"
original_available || exit 0
if ! command -v python3 >/dev/null 2>&1; then
    echo "skipped: python3 not found"
    exit 0
fi
limit=${CONFORMANCE_TIMEOUT:-15}
work=$(mktemp -d "${TMPDIR:-/tmp}/sitlog-hunt.XXXXXX")
if [ "${CONFORMANCE_KEEP:-0}" = 1 ]; then
    echo "work directory: $work"
else
    trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$work/shim"
printf '#!/bin/sh\nexec %s --traditional "$@"\n' "$(command -v swipl)" >"$work/shim/swipl"
chmod +x "$work/shim/swipl"

if [ $# -gt 0 ]; then
    progs=("$@")
else
    mapfile -t progs < <(find "$root/cli/tests/hunt" -name expect -printf '%h\n' | LC_ALL=C sort)
fi
status=0
for prog in "${progs[@]}"; do
    prog=$(cd "$prog" && pwd)
    name=$(basename "$prog")
    slot="$work/$name"
    original_prepare "$prog" "$slot/app"
    rm -f "$slot/app/expect"
    input=/dev/null
    [ -f "$prog/script.txt" ] && input="$prog/script.txt"
    PATH="$work/shim:$PATH" original_run json "$slot/app" main none "$input" \
        "$slot/original.json" "$slot/original.log" "$limit"
    got=$(python3 -c 'import json,sys; print("ok" if json.load(open(sys.argv[1]))["status"] == "ok" else "stops")' "$slot/original.json")
    want=$(sed -n 's/^original: *//p' "$prog/expect")
    if [ "$got" = "$want" ]; then
        echo "$name: $got"
    else
        echo "$name: $got (expected $want)"
        status=1
    fi
done
exit $status
