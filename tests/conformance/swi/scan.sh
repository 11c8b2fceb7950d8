#!/usr/bin/env bash
# The SWI-Prolog built-ins scan: which predicates the ORIGINAL SitLog tree's
# Prolog code and DMs call that sitlog-rs's embedded engine and prelude do
# not define.
#
# calls.pl (next to this file) lists, with SWI-Prolog, every predicate the
# tree's `*.pl` files (outside src/, the interpreter) and DMs call and do
# not define, classified `swi` (a built-in or autoloaded library predicate
# of SWI-Prolog), `interpreter` (defined by the original's src/ only) or
# `undefined` (by nobody). Those of the first two classes are then asked of
# our engine: a small application of ours (written to a temporary
# directory) runs under `sitlogc run` and tells, for each, whether our
# engine has it (a built-in, a library predicate, the prelude's), calling
# it with unbound arguments when nothing else tells (an existence error
# for that very predicate means missing). Nothing of the original is kept.
#
# Environment: SITLOG_HOME (the original's tree; required, else skip),
# swipl on PATH (else skip), SITLOGC (default target/release/sitlogc).
#
# Usage: tests/conformance/swi/scan.sh [-v]
# Prints `missing CLASS NAME/ARITY FILE:LINE` for each predicate our engine
# lacks, then a summary line; -v also lists those it has (`ok ...`) and the
# `undefined` ones. Exit status 1 when a `swi` predicate is missing.
set -u

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../../.." && pwd)
verbose=0
[ "${1:-}" = -v ] && verbose=1

skip() {
    echo "skipped: $*"
    exit 0
}
[ -n "${SITLOG_HOME:-}" ] || skip "SITLOG_HOME not set"
command -v swipl >/dev/null 2>&1 || skip "swipl not found"
[ -f "$SITLOG_HOME/src/init.pl" ] || skip "$SITLOG_HOME/src/init.pl not found"
sitlogc=${SITLOGC:-target/release/sitlogc}
case "$sitlogc" in
    /*) ;;
    *) sitlogc="$root/$sitlogc" ;;
esac
[ -x "$sitlogc" ] || skip "$sitlogc not built (cargo build --release --bin sitlogc)"

work=$(mktemp -d "${TMPDIR:-/tmp}/sitlog-swi-scan.XXXXXX")
trap 'rm -rf "$work"' EXIT

SITLOG_HOME=$SITLOG_HOME swipl -q "$here/calls.pl" >"$work/calls.txt" 2>/dev/null ||
    { echo "error: calls.pl failed"; exit 2; }

# The predicates to ask our engine about, as a Prolog list.
preds=$(awk '$1 == "swi" || $1 == "interpreter" { print $2 }' "$work/calls.txt" | paste -sd, -)
mkdir -p "$work/app"
cat >"$work/app/main.dm" <<'DM'
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : screen(apply(scan_missing(M), [m])) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
DM
cat >"$work/app/user_functions.pl" <<PL
scan_missing(_) :-
    findall(P, ( member(P, [$preds]), \\+ scan_has(P) ), Missing),
    assign_func_value(Missing).
% Known by a property, else called with unbound arguments: only an
% existence error for this very predicate means it is missing. Those that
% would read standard input are known by a property.
scan_has(N/A) :-
    functor(G, N, A),
    atom_concat('\$swi_', N, SN),
    (   catch(predicate_property(G, _), _, fail)
    ->  true
    ;   catch(current_predicate(SN/A), _, fail)      % renamed calls (swi.rs)
    ->  true
    ;   catch(current_predicate(N/A), _, fail)
    ->  true
    ;   memberchk(N/A, [read/1, get0/1, get/1, get_char/1, get_code/1, halt/0, halt/1])
    ->  fail
    ;   catch(( once(G) ; true ), E, true),
        \\+ ( nonvar(E), E = error(existence_error(procedure, N/A), _) )
    ).
PL
"$sitlogc" run "$work/app" >"$work/run.out" 2>"$work/run.err" ||
    { echo "error: sitlogc run failed:"; cat "$work/run.err"; exit 2; }
missing=$(sed -n 's/^Golem prints on screen: \[\(.*\)\]$/\1/p' "$work/run.err" | tr ',' '\n')
[ -n "$(sed -n '/^Golem prints on screen: /p' "$work/run.err")" ] ||
    { echo "error: no answer from sitlogc:"; cat "$work/run.err"; exit 2; }

status=0
n_missing=0
n_swi=0
while read -r class pred where; do
    case "$class" in
        swi | interpreter)
            [ "$class" = swi ] && n_swi=$((n_swi + 1))
            if printf '%s\n' "$missing" | grep -qxF -- "$pred"; then
                echo "missing $class $pred $where"
                n_missing=$((n_missing + 1))
                [ "$class" = swi ] && status=1
            elif [ $verbose = 1 ]; then
                echo "ok $class $pred $where"
            fi
            ;;
        *) [ $verbose = 1 ] && echo "$class $pred $where" ;;
    esac
done <"$work/calls.txt"
total=$(wc -l <"$work/calls.txt")
echo "$total predicates called and not defined by the tree ($n_swi of SWI-Prolog); $n_missing missing in sitlog-rs"
exit $status
