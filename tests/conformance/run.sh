#!/usr/bin/env bash
# Conformance check: run every application under dms/ that has a script.txt
# through the original SitLog interpreter (test mode) and through sitlogc,
# and compare the two results in our JSON convention. The original runs
# through the harness in original/ (original.sh, driver.pl in mode json).
#
# Environment:
#   SITLOG_HOME  checkout of the original interpreter (required, else skip)
#   swipl        SWI-Prolog on PATH (required, else skip)
#   SITLOGC      our binary (default target/release/sitlogc, relative to
#                the repository root)
#   CONFORMANCE_TIMEOUT  seconds per run of the original (default 60)
#   CONFORMANCE_KEEP=1   keep the work directory and print its path
#
# Usage: tests/conformance/run.sh [APP_DIR...]   (default: all of dms/)
#
# Output: one line per application, `APP: agree` or `APP: DIFFER: ...`.
# When SITLOGC does not exist yet, the original is compared with the
# application's expected.json instead, and the line says so.
# Exit status: 0 when nothing differs (or when skipped), 1 otherwise.
set -u

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)

# shellcheck source=original/original.sh
. "$here/original/original.sh"
original_available || exit 0

sitlogc=${SITLOGC:-target/release/sitlogc}
case "$sitlogc" in
    /*) ;;
    *) sitlogc="$root/$sitlogc" ;;
esac
have_ours=1
if [ ! -x "$sitlogc" ]; then
    have_ours=0
    echo "note: $sitlogc not found; comparing the original with expected.json only"
elif ! "$sitlogc" run --help >/dev/null 2>&1; then
    have_ours=0
    echo "note: $sitlogc has no 'run' command yet; comparing the original with expected.json only"
fi

timeout_s=${CONFORMANCE_TIMEOUT:-60}
known_file="$here/known_divergences.txt"
work=$(mktemp -d "${TMPDIR:-/tmp}/sitlog-conformance.XXXXXX")
if [ "${CONFORMANCE_KEEP:-0}" = 1 ]; then
    echo "work directory: $work"
else
    trap 'rm -rf "$work"' EXIT
fi

# Known divergences of one application: the paths listed for it.
known_paths() {
    local app=$1
    [ -f "$known_file" ] || return 0
    awk -v app="$app" '$0 !~ /^[ \t]*(#|$)/ && $1 == app { print $2 }' "$known_file"
}

failures=0
count=0
if [ $# -gt 0 ]; then
    apps=("$@")
else
    mapfile -t apps < <(find "$root/dms" -name script.txt -printf '%h\n' | LC_ALL=C sort)
fi

for app in "${apps[@]}"; do
    app=$(cd "$app" && pwd)
    name=${app#"$root/dms/"}
    name=${name#examples/}
    key=$(basename "$app")
    count=$((count + 1))
    slot="$work/$count"
    mkdir -p "$slot"
    original_prepare "$app" "$slot/app"
    original_run json "$slot/app" main none "$app/script.txt" "$slot/original.json" \
        "$slot/original.log" "$timeout_s"
    mapfile -t known < <(known_paths "$key")

    if [ $have_ours -eq 1 ]; then
        "$sitlogc" run "$app" --script "$app/script.txt" --format json \
            > "$slot/ours.json" 2> "$slot/ours.err"
        if [ ! -s "$slot/ours.json" ]; then
            echo "$name: DIFFER: sitlogc printed no JSON ($(head -c 200 "$slot/ours.err" | tr '\n' ' '))"
            failures=$((failures + 1))
            continue
        fi
        candidate="$slot/ours.json"
        label=""
    elif [ -f "$app/expected.json" ]; then
        candidate="$app/expected.json"
        label=" (original vs expected.json)"
    else
        echo "$name: skipped (no sitlogc, no expected.json)"
        continue
    fi

    verdict=$(swipl -q "$here/compare.pl" "$slot/original.json" "$candidate" "${known[@]}" 2>&1)
    rc=$?
    echo "$name: $verdict$label"
    [ $rc -eq 0 ] || failures=$((failures + 1))
done

if [ $count -eq 0 ]; then
    echo "no application with a script.txt under $root/dms"
fi
[ $failures -eq 0 ]
