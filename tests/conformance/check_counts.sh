#!/usr/bin/env bash
# Counts what `sitlogc check` reports on the ORIGINAL SitLog tree's own
# applications ($SITLOG_HOME/apps/*), per code: the errors must each be a
# kind the original fails on too (docs/guide/checking.md, "What stays an
# error", lists them with the figures this script printed), and everything
# the original runs must be at most a warning (issue 39). Nothing of the
# original is kept in this repository.
#
# Environment:
#   SITLOG_HOME  the original's tree (required, else skip)
#   SITLOGC      our binary (default target/release/sitlogc, else
#                target/debug/sitlogc)
#   CHECK_ALLOW  error codes allowed (default: the list below); an error
#                with another code fails the script
#
# Usage: tests/conformance/check_counts.sh
# Prints one line per application (`APP: N error(s) [CODE xN ...], M
# warning(s) [CODE xM ...]`), then the totals. Exit status: 0 when every
# error has an allowed code (or skipped), 1 otherwise, 2 on a usage problem.
set -u

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)

if [ -z "${SITLOG_HOME:-}" ] || [ ! -d "${SITLOG_HOME}/apps" ]; then
    echo "skipped: SITLOG_HOME is not set to the original's tree (with apps/)"
    exit 0
fi
if ! command -v python3 >/dev/null; then
    echo "skipped: python3 not found"
    exit 0
fi
sitlogc=${SITLOGC:-}
if [ -z "$sitlogc" ]; then
    for b in "$root/target/release/sitlogc" "$root/target/debug/sitlogc"; do
        [ -x "$b" ] && sitlogc=$b && break
    done
fi
if [ -z "$sitlogc" ] || [ ! -x "$sitlogc" ]; then
    echo "error: no sitlogc binary (build it, or set SITLOGC)" >&2
    exit 2
fi
# The kinds of error the original fails on too (docs/guide/checking.md).
allow=${CHECK_ALLOW:-"E0001 E0201 E0212 E0216 E0217 E0218 E0219 E0223 E0224 E0230 E0234 E0236 E0237"}

status=0
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
for app in "$SITLOG_HOME"/apps/*/; do
    [ -f "$app/models" ] || continue
    name=$(basename "$app")
    "$sitlogc" check --format json "$app" >"$tmp" 2>/dev/null
    code=$?
    if [ "$code" -ge 2 ]; then
        echo "$name: sitlogc check failed with status $code" >&2
        status=1
        continue
    fi
    python3 - "$name" "$allow" "$tmp" <<'PY' || status=1
import collections, json, sys
name, allow, path = sys.argv[1], sys.argv[2].split(), sys.argv[3]
count = {"error": collections.Counter(), "warning": collections.Counter()}
for line in open(path, encoding="utf-8"):
    d = json.loads(line)
    count[d["severity"]][d["code"]] += 1
def show(c):
    return " ".join(f"{k}x{v}" for k, v in sorted(c.items()))
e, w = count["error"], count["warning"]
print(f"{name}: {sum(e.values())} error(s) [{show(e)}], {sum(w.values())} warning(s) [{show(w)}]")
bad = sorted(set(e) - set(allow))
if bad:
    print(f"{name}: errors of a kind the original runs: {' '.join(bad)}", file=sys.stderr)
    sys.exit(1)
PY
done
exit $status
