#!/usr/bin/env bash
# Time per transition: the ORIGINAL SitLog interpreter (Prolog) against ours
# (the `sitlogc run` interpreter and a `sitlogc build --release` executable),
# on the same DMs and inputs.
#
# Environment:
#   SITLOG_HOME     checkout of the original interpreter (required, else skip)
#   swipl           SWI-Prolog on PATH (required, else skip)
#   SITLOGC         our binary (default target/release/sitlogc, relative to
#                   the repository root; built with cargo if missing)
#   BENCH_SIZES     sizes of the two loops, the Max of `main(Max)`
#                   (default "1000 10000"; e.g. "1000 10000 100000")
#   BENCH_REPEAT    runs per measurement of ours, the minimum counts (default 10)
#   ORIGINAL_REPEAT runs per measurement of the original (default 3)
#   ORIGINAL_TIMEOUT     seconds per run of the original (default 120)
#   ORIGINAL_STACK_LIMIT swipl --stack-limit (default 8g)
#   ORIGINAL_MAX_TRANSITIONS  do not run the original above this many
#                   transitions (default 20000): it needs ~350 KB of Prolog
#                   stack per transition, see below
#   BENCH_COMPILED=0  do not build compiled executables
#   BENCH_KEEP=1    keep the work directory (logs, build output) and print it
#
# Usage: benches/original.sh [WORKLOAD...]
#   workloads: counter_loop pipe_calls appendix_a (default: all three)
#
# Workloads (all ours; nothing of the original is copied into this
# repository, it is only run from $SITLOG_HOME, as tests/conformance does):
#   counter_loop  benches/dms/counter_loop, main(Max): a neutral loop with a
#                 local counter, Max+1 transitions, no input
#   pipe_calls    benches/dms/pipe_calls, main(Max) with in_arg 0: Max calls
#                 of an embedded DM, 4 transitions per call (4*Max+1)
#   appendix_a    dms/examples/appendix_a with its script.txt (12
#                 transitions, Prolog user functions)
#
# Method.
# * Every figure is the wall-clock time of a whole process (date +%s%N
#   around it), the minimum over BENCH_REPEAT (ours) or ORIGINAL_REPEAT
#   (original) runs; appendix_a, only 12 transitions, takes 4 times as many.
# * Start-up is removed by difference: each run is paired with an otherwise
#   identical base run that makes almost no transitions, and
#       us/transition = (T(run) - T(base)) / (n(run) - n(base)).
#   The base of the loops is main(1) (2 resp. 5 transitions); the base of
#   appendix_a is the same application with an empty script (everything is
#   loaded, then the first read meets the end of the input: 0 transitions).
#   This takes out process and SWI-Prolog start-up, loading the original's
#   sources and the DMs (about 70 ms for the original), and the same for us.
#   When T(run) - T(base) is within the noise (the sum of median - minimum
#   of both), the figure is shown as an upper bound `<U` (and the ratio as a
#   bound `>R`): ours at 10^3 transitions and on appendix_a can be that fast.
# * n (transitions) is counted by our interpreter with --trace (one line
#   per transition) and checked against the length of the original's
#   history (embedded histories flattened); a mismatch is reported.
# * Ours: `sitlogc run APP --main 'main(N)' [--in-arg 0] --history none
#   --format json` (appendix_a: `--script script.txt`); the compiled
#   executable takes the same options. It is built once per workload into
#   the work directory with `sitlogc build APP -o FILE --release`; when the
#   build fails the column says n/a.
# * Original: the harness in tests/conformance/original/ (ours; driver.pl
#   in mode count) loads $SITLOG_HOME/src/init.pl,
#   asserts the facts of a test-mode start_init/0 and calls execute_md/8 for
#   the main DM, input on stdin (/dev/null for the loops). As in any run of
#   the original, the history is KEPT (there is no switch; execute_md/8
#   extends it with append/3 at every transition, so a transition costs
#   O(length of the history)) and the log file is written; its console
#   output goes to /dev/null. Its choice points keep every intermediate
#   state alive, ~350 KB of stack per transition, so 10^4 transitions need
#   ~3.5 GB (hence ORIGINAL_STACK_LIMIT and ORIGINAL_MAX_TRANSITIONS).
# * counter_loop writes its action as a list, `[inc(n, N)]`: the original
#   cannot perform a bare number (the value of `inc(n, N)`); its
#   execute_actions_arc/1 fails on one, while a list of numbers is a no-op.
#
# Output: a table; columns in microseconds per transition; the ratios are
# original/interpreter and original/compiled. Exit status 0 (also when
# skipped), 1 when a run of ours failed, 2 on usage errors.
set -u

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)

# The harness shared with tests/conformance: original_available,
# original_prepare, original_run (driver.pl in mode count).
# shellcheck source=../tests/conformance/original/original.sh
. "$root/tests/conformance/original/original.sh"
original_available || exit 0

sitlogc=${SITLOGC:-target/release/sitlogc}
case "$sitlogc" in
    /*) ;;
    *) sitlogc="$root/$sitlogc" ;;
esac
if [ ! -x "$sitlogc" ]; then
    if [ -z "${SITLOGC:-}" ]; then
        echo "building sitlogc (cargo build --release --bin sitlogc)" >&2
        (cd "$root" && cargo build --release --bin sitlogc) >&2 || {
            echo "error: cannot build sitlogc" >&2
            exit 1
        }
    else
        echo "error: $sitlogc not found" >&2
        exit 2
    fi
fi

sizes=${BENCH_SIZES:-1000 10000}
repeat=${BENCH_REPEAT:-10}
orig_repeat=${ORIGINAL_REPEAT:-3}
orig_timeout=${ORIGINAL_TIMEOUT:-120}
orig_stack=${ORIGINAL_STACK_LIMIT:-8g}
orig_max=${ORIGINAL_MAX_TRANSITIONS:-20000}
compiled=${BENCH_COMPILED:-1}

if [ $# -gt 0 ]; then
    workloads=("$@")
else
    workloads=(counter_loop pipe_calls appendix_a)
fi
for w in "${workloads[@]}"; do
    case "$w" in
        counter_loop | pipe_calls | appendix_a) ;;
        *) echo "error: unknown workload $w (counter_loop, pipe_calls, appendix_a)" >&2; exit 2 ;;
    esac
done
for s in $sizes; do
    case "$s" in
        '' | *[!0-9]*) echo "error: BENCH_SIZES must be positive integers: $s" >&2; exit 2 ;;
    esac
done

work=$(mktemp -d "${TMPDIR:-/tmp}/sitlog-bench-original.XXXXXX")
if [ "${BENCH_KEEP:-0}" = 1 ]; then
    echo "work directory: $work"
else
    trap 'rm -rf "$work"' EXIT
fi
: > "$work/empty.txt"
notes=()
failures=0

now_ns() { date +%s%N; }

# best_ns REPEAT STDIN CMD...: prints "MIN JITTER" in ns over REPEAT runs of
# CMD with stdin from STDIN and all output discarded; JITTER is median -
# minimum, the noise scale of MIN. Sets `last_rc` to the exit status of the
# last run.
last_rc=0
best_ns() {
    local n=$1 input=$2 i t0 t1
    local -a ts=()
    shift 2
    for ((i = 0; i < n; i++)); do
        t0=$(now_ns)
        "$@" < "$input" > /dev/null 2>&1
        last_rc=$?
        t1=$(now_ns)
        ts+=($((t1 - t0)))
    done
    summarize "${ts[@]}"
}

# summarize NS...: "MIN JITTER" of the samples.
summarize() {
    printf '%s\n' "$@" | sort -n | awk '{ v[NR] = $1 } END { print v[1], v[int((NR + 1) / 2)] - v[1] }'
}

# Our copy of a workload: the application as it is.
prepare_ours() {
    local app=$1 copy=$2
    mkdir -p "$copy"
    cp -R "$app/." "$copy/"
}

# run_original COPY MAIN IN_ARG INPUT RESULT: one run of the original.
run_original() {
    original_run count "$1" "$2" "$3" "$4" "$5" /dev/null "$orig_timeout" \
        --stack-limit="$orig_stack"
}

# best_original REPEAT COPY MAIN IN_ARG INPUT: "MIN JITTER" in ns over
# REPEAT runs (see best_ns); the last run's result line is left in
# $work/orig.result. Stops repeating after a failed run.
best_original() {
    local n=$1 i t0 t1
    local -a ts=()
    shift
    for ((i = 0; i < n; i++)); do
        t0=$(now_ns)
        run_original "$@" "$work/orig.result"
        t1=$(now_ns)
        ts+=($((t1 - t0)))
        case "$(cut -d' ' -f3- "$work/orig.result")" in
            ok) ;;
            *) break ;;
        esac
    done
    summarize "${ts[@]}"
}

# per_us "T_RUN J_RUN" "T_BASE J_BASE" N_RUN N_BASE: microseconds per
# transition. When the difference of the minima is within the noise (the sum
# of the two jitters), prints "<U", U being an upper bound per transition.
per_us() {
    awk -v r="$1" -v b="$2" -v n="$3" -v m="$4" 'BEGIN {
        split(r, R, " "); split(b, B, " ");
        dn = n - m; d = R[1] - B[1]; j = R[2] + B[2];
        if (dn <= 0) print "n/a";
        else if (d <= j) printf "<%.2f\n", ((d > 0 ? d : 0) + j) / 1000 / dn;
        else printf "%.2f\n", d / 1000 / dn }'
}

# ratio A B: A / B as "12x"; "<U" operands give ">" or "<" bounds.
ratio() {
    awk -v a="$1" -v b="$2" 'BEGIN {
        pa = (a ~ /^</); pb = (b ~ /^</); sub(/^</, "", a); sub(/^</, "", b);
        if (a !~ /^[0-9.]+$/ || b !~ /^[0-9.]+$/ || b <= 0 || (pa && pb)) { print "n/a"; exit }
        q = a / b; printf (q < 10 ? "%s%.1fx\n" : "%s%.0fx\n"), (pb ? ">" : (pa ? "<" : "")), q }'
}

# count_transitions OUT_TRACE CMD...: runs CMD once with --trace; prints the
# number of transitions.
count_transitions() {
    local trace=$1
    shift
    rm -f "$trace"
    "$@" --trace "$trace" > /dev/null 2>&1
    if [ -f "$trace" ]; then wc -l < "$trace" | tr -d ' '; else echo 0; fi
}

rows=()
add_row() { rows+=("$(printf '%-13s %7s %11s %10s %12s %10s %12s %14s' "$@")"); }

for w in "${workloads[@]}"; do
    case "$w" in
        appendix_a) app="$root/dms/examples/appendix_a" ;;
        *) app="$root/benches/dms/$w" ;;
    esac
    slot="$work/$w"
    prepare_ours "$app" "$slot/ours/$w" "$w"
    ours_app="$slot/ours/$w"
    original_prepare "$ours_app" "$slot/orig"
    orig_app="$slot/orig"

    exe=""
    if [ "$compiled" = 1 ]; then
        echo "building the compiled $w (sitlogc build --release) ..." >&2
        if (cd "$root" && "$sitlogc" build "$ours_app" -o "$slot/$w.exe" --release) \
            > "$slot/build.log" 2>&1 && [ -x "$slot/$w.exe" ]; then
            exe="$slot/$w.exe"
        else
            notes+=("$w: compiled build failed ($(grep -m1 -E '^error' "$slot/build.log" | cut -c1-120)); column n/a")
        fi
    fi

    # The runs of this workload, the base run first: main DM, input, label.
    in_arg=none
    in_opt=()
    [ "$w" = pipe_calls ] && { in_arg=0; in_opt=(--in-arg 0); }
    if [ "$w" = appendix_a ]; then
        mains=(main main)
        scripts=("$work/empty.txt" "$app/script.txt")
        labels=(base "script")
        ours_rep=$((repeat * 4))
        orig_rep=$((orig_repeat * 4))
    else
        mains=("main(1)")
        scripts=("$work/empty.txt")
        labels=(base)
        for s in $sizes; do
            mains+=("main($s)")
            scripts+=("$work/empty.txt")
            labels+=("$s")
        done
        ours_rep=$repeat
        orig_rep=$orig_repeat
    fi

    base_n=0 base_i=0 base_c=0 base_o=0
    for k in "${!mains[@]}"; do
        main=${mains[$k]}
        script=${scripts[$k]}
        label=${labels[$k]}
        echo "running $w $label ..." >&2
        run=("$sitlogc" run "$ours_app" --main "$main" "${in_opt[@]}" --history none --format json)
        exe_run=()
        [ -n "$exe" ] && exe_run=("$exe" --main "$main" "${in_opt[@]}" --history none --format json)
        if [ "$w" = appendix_a ]; then
            run+=(--script "$script")
            [ -n "$exe" ] && exe_run+=(--script "$script")
        fi

        n=$(count_transitions "$slot/trace.jsonl" "${run[@]}")
        t_i=$(best_ns "$ours_rep" /dev/null "${run[@]}")
        rc_i=$last_rc
        t_c=""
        if [ -n "$exe" ]; then
            t_c=$(best_ns "$ours_rep" /dev/null "${exe_run[@]}")
            rc_c=$last_rc
        fi
        # ours must succeed, except the base run of appendix_a (end of input)
        if [ "$label" != base ] || [ "$w" != appendix_a ]; then
            if [ "$rc_i" -ne 0 ]; then
                notes+=("$w $label: sitlogc run exited $rc_i")
                failures=$((failures + 1))
            fi
            if [ -n "$exe" ] && [ "$rc_c" -ne 0 ]; then
                notes+=("$w $label: compiled executable exited $rc_c")
                failures=$((failures + 1))
            fi
        fi

        if [ "$n" -gt "$orig_max" ]; then
            t_o="" o_status="skipped(>$orig_max transitions)"
            notes+=("$w $label: original skipped, $n transitions > ORIGINAL_MAX_TRANSITIONS=$orig_max (~350 KB of stack each)")
        else
            t_o=$(best_original "$orig_rep" "$orig_app" "$main" "$in_arg" "$script")
            read -r o_n o_secs o_status < "$work/orig.result"
            if [ "$label" = base ] && [ "$w" = appendix_a ]; then
                # the base run must end at the first read of the empty input
                case "$o_status" in
                    *past_end_of_stream*) o_status=ok ;;
                esac
            elif [ "$o_status" = ok ] && [ "$o_n" -ne "$n" ]; then
                notes+=("$w $label: the original made $o_n transitions, ours $n")
            fi
            [ "$o_status" = ok ] || notes+=("$w $label: original: $(cut -c1-160 <<<"$o_status")")
            [ "$label" = base ] || notes+=("$w $label: original's execute_md/8 alone (in-process clock): $(awk -v s="$o_secs" -v n="$n" 'BEGIN { printf "%.2f", s * 1e6 / n }') us/transition")
        fi

        if [ "$label" = base ]; then
            base_n=$n base_i=$t_i base_c=$t_c base_o=$t_o
            [ "$o_status" = ok ] || base_o=""
            continue
        fi
        u_i=$(per_us "$t_i" "$base_i" "$n" "$base_n")
        u_c=n/a
        [ -n "$exe" ] && [ -n "$base_c" ] && u_c=$(per_us "$t_c" "$base_c" "$n" "$base_n")
        u_o=n/a
        if [ "$o_status" = ok ] && [ -n "$base_o" ]; then
            u_o=$(per_us "$t_o" "$base_o" "$n" "$base_n")
        elif [ "$o_status" != ok ]; then
            u_o=$(cut -d'(' -f1 <<<"$o_status")
        fi
        size=$label
        [ "$w" = appendix_a ] && size=script
        add_row "$w" "$size" "$n" "$u_o" "$u_i" "$u_c" "$(ratio "$u_o" "$u_i")" "$(ratio "$u_o" "$u_c")"
    done
done

echo
echo "microseconds per transition (start-up subtracted; original keeps its history, ours --history none)"
printf '%-13s %7s %11s %10s %12s %10s %12s %14s\n' workload size transitions original \
    interpreter compiled orig/interp orig/compiled
[ ${#rows[@]} -eq 0 ] || printf '%s\n' "${rows[@]}"
if [ ${#notes[@]} -gt 0 ]; then
    echo
    printf 'note: %s\n' "${notes[@]}"
fi
[ $failures -eq 0 ]
