#!/usr/bin/env bash
# Runs the tasks of the ORIGINAL SitLog tree's own applications, as their
# authors wrote them, on the original interpreter and on
# `sitlogc run --legacy`, each from a fresh copy of the original's tree, and
# compares the runs (legacy_demos.py: transitions, DM/situation sequence,
# actions, utterances in order). With LEGACY_COMPILED=1, also on the task
# `sitlogc build --legacy` compiles from each app (one build per app, run
# for each of its tasks), compared with the original's run as ours is and
# with `sitlogc run --legacy`'s (legacy_demos.py --same: stdout, stderr and
# exit status identical).
#
# The tasks are the files legacy_apps/APP/TASK.txt next to this script: the
# inputs a user types in test mode, one term a line (for a dispatcher app,
# `res(TASK).` and `ok.` first), written by us from the DMs; APP is the
# directory under $SITLOG_HOME/apps, run by the original through its own
# launcher $SITLOG_HOME/scripts/APP (`test` mode). Each is a task that the
# original completes with those inputs: a run counts only when the original
# ends its main DM without reading past the inputs and without an error of
# its own. Nothing of the original is kept in this repository.
#
# Environment:
#   SITLOG_HOME  the original's tree (required, else skip)
#   swipl        SWI-Prolog on PATH (required, else skip); the original runs
#                as `swipl --traditional` (SWI-6 lists, see legacy_demos.sh)
#   SITLOGC      our binary (default target/release/sitlogc)
#   LEGACY_KB    our KB modes to run, default "prolog native"
#   LEGACY_COMPILED=1    also run the compiled tasks (a build per app takes
#                        minutes: set SITLOGC_CACHE_DIR to share its cache);
#                        =only: the compiled tasks and the original only
#   LEGACY_TASKS         a directory keeping the compiled tasks (legacy_task.sh)
#   CONFORMANCE_TIMEOUT  seconds per run (default 120)
#   CONFORMANCE_KEEP=1   keep the work directory and print its path
#   LEGACY_DATE          the clock every run starts at, when `faketime`
#                        (libfaketime) is on PATH: default a Monday,
#                        "2027-06-07 20:00:00" UTC; `now` runs on the real
#                        clock. The original's own `time` task fails on a
#                        Sunday (its user function `hora` looks up a weekday
#                        7 that its table lacks) whatever we do; a fixed clock
#                        gives both sides the same day and hour.
#
# Usage: tests/conformance/legacy_apps.sh [APP/TASK]...   (default: all)
# Prints one line per task and KB mode (`APP/TASK kb=MODE: agree (N
# transitions, M utterances; time: original S s (cpu C s), sitlogc S s
# (cpu C s))` or `... DIFFER` with the first differences; times are
# wall-clock seconds and CPU seconds (user + system, children included) of
# the whole process, the original's launcher included), then `N of M tasks
# agree` and the runs where sitlogc used more CPU time than the original
# (the fairer figure on a loaded machine). Exit status: 0 when all agree
# (or skipped), 1 otherwise.
set -u
# Every run (the original's and ours) starts at the same fake time, when we
# can: each run gets its own `faketime`, so a slow pass cannot put the
# original's run and ours in different minutes (the clock ticks from the
# start of each run, not of the pass).
clock=()
if [ "${LEGACY_DATE:-}" != now ] && command -v faketime >/dev/null 2>&1; then
    clock=(faketime "${LEGACY_DATE:-2027-06-07 20:00:00}")
fi

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)

# shellcheck source=original/original.sh
. "$here/original/original.sh"
original_legacy_setup legacy-apps 120 || exit 0
read -r -a kbs <<<"${LEGACY_KB:-prolog native}"
# shellcheck source=legacy_task.sh
. "$here/legacy_task.sh"

# A fresh copy of the original's tree (tasks rewrite its KB files).
fresh() {
    rm -rf "$1"
    mkdir -p "$1"
    (cd "$SITLOG_HOME" && tar --exclude=./.git -cf - .) | (cd "$1" && tar -xf -)
}

# The original ended its main DM without reading past the inputs and
# without going through one of its own errors ("Press Ctrl. C and abort" or
# ", Abort", printed when a function or a next situation fails; it then
# leaves the DM).
completed() {
    grep -aq "'Dialogue manager ends'" "$1" && ! grep -aq "end_of_file" "$1" &&
        ! grep -aq "Press Ctrl. C" "$1"
}

tasks=("$@")
if [ ${#tasks[@]} -eq 0 ]; then
    while IFS= read -r f; do
        tasks+=("${f%.txt}")
    done < <(cd "$here/legacy_apps" && find . -name '*.txt' | sed 's|^\./||' | LC_ALL=C sort)
fi
status=0
total=0
agreed=0
slower=()
now() { date +%s.%N; }
secs() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", b - a }'; }
# CPU seconds (user + system) of a command's process and its children, as
# bash's `time` reports them with TIMEFORMAT='%U %S' in the file $1.
cpu() { awk '{ printf "%.2f", $1 + $2 }' "$1"; }
TIMEFORMAT='%U %S'
for task in "${tasks[@]}"; do
    app=${task%%/*}
    input="$here/legacy_apps/$task.txt"
    total=$((total + 1))
    if [ ! -f "$input" ] || [ ! -f "$SITLOG_HOME/scripts/$app" ]; then
        echo "$task: DIFFER: no $input or no launcher $SITLOG_HOME/scripts/$app"
        status=1
        continue
    fi
    d="$work/${task//\//.}"
    mkdir -p "$d"
    fresh "$d/tree"
    t0=$(now)
    { time (cd "$d/tree" && PATH="$work/shim:$PATH" SITLOG_HOME="$d/tree/" \
        ${clock[@]+"${clock[@]}"} timeout "$limit" bash "scripts/$app" test <"$input" >"$d/original.out" 2>&1); } 2>"$d/cpu-original"
    t_original=$(secs "$t0" "$(now)")
    c_original=$(cpu "$d/cpu-original")
    if ! completed "$d/original.out"; then
        echo "$task: DIFFER: the original does not complete this task with these inputs"
        status=1
        rm -rf "$d/tree"
        continue
    fi
    ok=1
    for kb in "${kbs[@]}"; do
      if [ "${LEGACY_COMPILED:-0}" != only ]; then
        fresh "$d/tree"
        t0=$(now)
        { time (cd "$d/tree" && SITLOG_HOME="$d/tree/" ${clock[@]+"${clock[@]}"} timeout "$limit" \
            "$sitlogc" run "apps/$app" --legacy --legacy-kb "$kb" --script "$input" \
            >"$d/ours-$kb.out" 2>"$d/ours-$kb.err"); } 2>"$d/cpu-$kb"
        rc=$?
        t_ours=$(secs "$t0" "$(now)")
        c_ours=$(cpu "$d/cpu-$kb")
        times="time: original $t_original s (cpu $c_original s), sitlogc $t_ours s (cpu $c_ours s)"
        if awk -v a="$c_ours" -v b="$c_original" 'BEGIN { exit !(a > b) }'; then
            slower+=("$task kb=$kb ($times)")
        fi
        python3 "$here/legacy_demos.py" "$d/original.out" "$d/ours-$kb.out" "$d/ours-$kb.err" \
            >"$d/compare-$kb.txt"
        cmp=$?
        if [ "$cmp" = 0 ] && [ "$rc" = 0 ]; then
            echo "$task kb=$kb: agree ($(head -n 1 "$d/compare-$kb.txt"); $times)"
        else
            echo "$task kb=$kb: DIFFER (exit status $rc)"
            sed 's/^/    /' "$d/compare-$kb.txt"
            [ "$rc" = 0 ] || tail -n 3 "$d/ours-$kb.err" | sed 's/^/    stderr: /'
            ok=0
            status=1
        fi
      fi
        [ "${LEGACY_COMPILED:-0}" != 0 ] || continue
        if ! task_exe=$(legacy_task "apps/$app"); then
            echo "$task kb=$kb compiled: DIFFER (no compiled task)"
            ok=0
            status=1
            continue
        fi
        fresh "$d/tree"
        t0=$(now)
        (cd "$d/tree" && SITLOG_HOME="$d/tree/" ${clock[@]+"${clock[@]}"} timeout "$limit" \
            "$task_exe" --legacy --legacy-kb "$kb" --script "$input" \
            >"$d/task-$kb.out" 2>"$d/task-$kb.err")
        rc_task=$?
        t_task=$(secs "$t0" "$(now)")
        python3 "$here/legacy_demos.py" "$d/original.out" "$d/task-$kb.out" "$d/task-$kb.err" \
            >"$d/compare-task-$kb.txt"
        cmp=$?
        if [ "${LEGACY_COMPILED:-0}" = only ]; then
            rc=0 same=0
            echo "not run (LEGACY_COMPILED=only)" >"$d/same-$kb.txt"
        else
            legacy_same "$d/ours-$kb" "$d/task-$kb" >"$d/same-$kb.txt"
            same=$?
        fi
        if [ "$cmp" = 0 ] && [ "$same" = 0 ] && [ "$rc" = "$rc_task" ]; then
            echo "$task kb=$kb compiled: agree ($(head -n 1 "$d/compare-task-$kb.txt")), $(head -n 1 "$d/same-$kb.txt") (compiled task $t_task s)"
        else
            echo "$task kb=$kb compiled: DIFFER (exit status $rc_task, run --legacy $rc)"
            sed 's/^/    against the original: /' "$d/compare-task-$kb.txt"
            sed 's/^/    against run --legacy: /' "$d/same-$kb.txt"
            ok=0
            status=1
        fi
    done
    [ $ok = 1 ] && agreed=$((agreed + 1))
    # One copy of the tree at a time (7-8 MB each).
    [ "${CONFORMANCE_KEEP:-0}" = 1 ] || rm -rf "$d/tree"
done
echo "$agreed of $total tasks agree"
if [ ${#slower[@]} -gt 0 ]; then
    echo "sitlogc used more CPU time than the original on ${#slower[@]} run(s):"
    printf '    %s\n' "${slower[@]}"
fi
exit $status
