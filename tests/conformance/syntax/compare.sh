#!/usr/bin/env bash
# Conformance of sitlog-syntax's reader and writeq printer with SWI-Prolog's
# read/1 + writeq on the public SitLog corpus.
#
#   SITLOG_HOME=/path/to/sitlog/checkout tests/conformance/syntax/compare.sh [dm|side|all]
#
# dm   (default): the canonical DM files (syntax.md §6): *.dm regular files under
#      behaviors/, recovery_protocols/ and apps/, leaving out backups (backup, bkp),
#      copies, old/ folders and editor lock files (.#*, *~).
# side: the side files of the applications (models, global_vars.pl,
#      basic_actions.pl, expectation_types.pl, user_functions.pl, templates.pl),
#      with the same exclusions.
# Each file is dumped by swi_dump.pl (SWI-Prolog) and by the `dump` example of
# sitlog-syntax; the dumps must be identical line for line. Files SWI rejects
# must be rejected by us too: both positions are printed.
# Skips (exit 0) when SITLOG_HOME or swipl is missing. Exit 1 on any mismatch.
# Work files (both dumps of every file) stay in $OUT (default: a temp dir).
set -u
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
mode=${1:-dm}

if [ -z "${SITLOG_HOME:-}" ] || [ ! -d "${SITLOG_HOME:-}" ]; then
    echo "skip: SITLOG_HOME is not set to a SitLog checkout"
    exit 0
fi
if ! command -v swipl >/dev/null 2>&1; then
    echo "skip: swipl (SWI-Prolog) is not installed"
    exit 0
fi

cargo build --release -q -p sitlog-syntax --example dump --manifest-path "$root/Cargo.toml" || exit 2
target=${CARGO_TARGET_DIR:-$root/target}
dump="$target/release/examples/dump"
[ -x "$dump" ] || { echo "cannot find $dump"; exit 2; }

OUT=${OUT:-$(mktemp -d)}
mkdir -p "$OUT"

exclude='backup|bkp|copy|(^|/)old/|(^|/)\.#|~$'
list_dm() {
    (cd "$SITLOG_HOME" && find behaviors recovery_protocols apps -name '*.dm' -type f 2>/dev/null) \
        | grep -viE "$exclude" | LC_ALL=C sort
}
list_side() {
    (cd "$SITLOG_HOME" && find apps -type f \( -name models -o -name global_vars.pl \
        -o -name basic_actions.pl -o -name expectation_types.pl \
        -o -name user_functions.pl -o -name templates.pl \) 2>/dev/null) \
        | grep -viE "$exclude" | LC_ALL=C sort
}

# Dumps one file both ways; prints one status line:
#   same F | differ F | both-reject F SWI=l:c US=l:c (msg) | swi-reject F ... | us-reject F ...
one() {
    f=$1
    key=$(printf '%s' "$f" | tr '/ ()' '____')
    swi="$OUT/$key.swi"; us="$OUT/$key.us"; err="$OUT/$key.err"
    swipl -q "$here/swi_dump.pl" -- "$SITLOG_HOME/$f" >"$swi" 2>/dev/null
    "$dump" "$SITLOG_HOME/$f" --stop >"$us" 2>"$err"
    swi_err=$(grep -m1 '^SYNTAX_ERROR ' "$swi" | cut -d' ' -f2-)
    us_err=$(head -n1 "$err" | sed "s|^$SITLOG_HOME/$f:||")
    if [ -n "$swi_err" ] && [ -n "$us_err" ]; then
        echo "both-reject $f SWI=${swi_err} | US=${us_err}"
    elif [ -n "$swi_err" ]; then
        echo "swi-reject $f SWI=${swi_err}"
    elif [ -n "$us_err" ]; then
        echo "us-reject $f US=${us_err}"
    elif cmp -s "$swi" "$us"; then
        echo "same $f"
    else
        echo "differ $f"
    fi
}
export -f one
export SITLOG_HOME OUT here dump

run() {
    local kind=$1 files
    files=$("list_$kind")
    n=$(printf '%s\n' "$files" | grep -c .)
    echo "== $kind: $n files"
    printf '%s\n' "$files" | tr '\n' '\0' | xargs -0 -P "${JOBS:-2}" -I{} bash -c 'one "$1"' _ {} \
        | LC_ALL=C sort -k2 >"$OUT/$kind.status"
    for s in same differ both-reject swi-reject us-reject; do
        printf '%-12s %d\n' "$s" "$(grep -c "^$s " "$OUT/$kind.status")"
    done
    grep -v '^same ' "$OUT/$kind.status"
    # One differing line per differing file, to see what is wrong.
    grep '^differ ' "$OUT/$kind.status" | cut -d' ' -f2- | while read -r f; do
        key=$(printf '%s' "$f" | tr '/ ()' '____')
        diff <(tr ',' '\n' <"$OUT/$key.swi") <(tr ',' '\n' <"$OUT/$key.us") | head -4
    done
    ! grep -qE '^(differ|swi-reject|us-reject) ' "$OUT/$kind.status"
}

status=0
case $mode in
    dm) run dm || status=1 ;;
    side) run side || status=1 ;;
    all) run dm || status=1; run side || status=1 ;;
    *) echo "usage: $0 [dm|side|all]"; exit 2 ;;
esac
echo "work files in $OUT"
exit $status
