#!/usr/bin/env bash
# Runs the 2021 paper's two demonstrations, as their authors wrote them, on
# the original SitLog interpreter, on `sitlogc run --legacy` and on the task
# `sitlogc build --legacy` compiles from the application, each in a fresh
# copy of the original's tree, and compares the runs: ours with the
# original's (legacy_demos.py: transitions, DM/situation sequence, actions,
# utterances in order), and the compiled task with `sitlogc run --legacy`
# (legacy_demos.py --same: stdout and stderr identical, with the text
# output and with --format json). Ours runs twice: with the original's KB
# layer as it is (--legacy-kb prolog) and served by sitlog-kb
# (--legacy-kb native).
#
#   preferences       apps/test_behaviors, dispatcher answer res(preferences).
#   demo_supermarket  apps/german_open_2019, dispatcher answer res(demo_supermarket).
#
# The inputs are read from each demo's README in the original's tree (the
# indented lines after "enter the following answers"); nothing of the
# original is kept in this repository.
#
# Environment:
#   SITLOG_HOME  the original's tree (required, else skip)
#   swipl        SWI-Prolog on PATH (required, else skip); the original is
#                run as `swipl --traditional` (SWI-6 lists, which its
#                action code needs; a wrapper first on PATH)
#   SITLOGC      our binary (default target/release/sitlogc)
#   LEGACY_COMPILED=0    skip the compiled tasks (built once per app with
#                        `sitlogc build --legacy`, minutes each; set
#                        SITLOGC_CACHE_DIR to share its build cache)
#   LEGACY_TASKS         a directory keeping the compiled tasks (legacy_task.sh)
#   CONFORMANCE_TIMEOUT  seconds per run (default 300)
#   CONFORMANCE_KEEP=1   keep the work directory and print its path
#
# Usage: tests/conformance/legacy_demos.sh [preferences|demo_supermarket]...
# Exit status: 0 when both agree (or when skipped), 1 otherwise.
set -u

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)

# shellcheck source=original/original.sh
. "$here/original/original.sh"
original_legacy_setup legacy 300 || exit 0

# A fresh copy of the original's tree (the demos rewrite its KB files).
fresh() {
    mkdir -p "$1"
    (cd "$SITLOG_HOME" && tar --exclude=./.git -cf - .) | (cd "$1" && tar -xf -)
}

now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", b - a }'; }

# shellcheck source=legacy_task.sh
. "$here/legacy_task.sh"

demos=("$@")
[ ${#demos[@]} -gt 0 ] || demos=(preferences demo_supermarket)
status=0
for demo in "${demos[@]}"; do
    case "$demo" in
        preferences) app=apps/test_behaviors launcher=scripts/test_behaviors ;;
        demo_supermarket) app=apps/german_open_2019 launcher=scripts/german_open_2019 ;;
        *) echo "$demo: unknown demo (preferences or demo_supermarket)"; status=1; continue ;;
    esac
    readme=$(find "$SITLOG_HOME/$app" -path "*/$demo/README.md" | head -n 1)
    if [ -z "$readme" ]; then
        echo "$demo: DIFFER: no README.md with the inputs under $SITLOG_HOME/$app"
        status=1
        continue
    fi
    d="$work/$demo"
    mkdir -p "$d"
    awk '/following answers/ { on = 1; next } on && /^    [^ ].*\.[ \t]*$/ { sub(/^    /, ""); print }' \
        "$readme" >"$d/inputs.txt"
    # The original, as its launcher runs it.
    fresh "$d/original"
    t0=$(now)
    (cd "$d/original" && PATH="$work/shim:$PATH" SITLOG_HOME="$d/original/" \
        timeout "$limit" bash "$launcher" test <"$d/inputs.txt" >"$d/original.out" 2>&1)
    t1=$(now)
    echo "$demo: $(wc -l <"$d/inputs.txt") inputs; original $(elapsed "$t0" "$t1") s"
    # Ours, from the same kind of tree: the original's KB layer run as it
    # is (prolog), then served by sitlog-kb (native).
    for kb in prolog native; do
        fresh "$d/ours-$kb"
        t2=$(now)
        (cd "$d/ours-$kb" && SITLOG_HOME="$d/ours-$kb/" timeout "$limit" \
            "$sitlogc" run "$app" --legacy --legacy-kb "$kb" --script "$d/inputs.txt" \
            >"$d/ours-$kb.out" 2>"$d/ours-$kb.err")
        rc=$?
        t3=$(now)
        echo "  sitlogc --legacy-kb $kb: $(elapsed "$t2" "$t3") s (exit status $rc)"
        python3 "$here/legacy_demos.py" "$d/original.out" "$d/ours-$kb.out" "$d/ours-$kb.err" | sed 's/^/    /'
        if [ "${PIPESTATUS[0]}" != 0 ] || [ "$rc" != 0 ]; then
            status=1
        fi
        # The compiled task: against the original, then against the run
        # above (text output), then both again with --format json.
        [ "${LEGACY_COMPILED:-1}" = 1 ] || continue
        task=$(legacy_task "$app") || { status=1; continue; }
        for format in text json; do
            fresh "$d/run-$kb-$format"
            fresh "$d/task-$kb-$format"
            if [ $format = json ]; then
                (cd "$d/run-$kb-$format" && SITLOG_HOME="$d/run-$kb-$format/" timeout "$limit" \
                    "$sitlogc" run "$app" --legacy --legacy-kb "$kb" --script "$d/inputs.txt" --format json \
                    >"$d/ours-$kb-json.out" 2>"$d/ours-$kb-json.err")
                rc=$?
            fi
            t2=$(now)
            (cd "$d/task-$kb-$format" && SITLOG_HOME="$d/task-$kb-$format/" timeout "$limit" \
                "$task" --legacy --legacy-kb "$kb" --script "$d/inputs.txt" --format "$format" \
                >"$d/task-$kb-$format.out" 2>"$d/task-$kb-$format.err")
            rc_task=$?
            t3=$(now)
            suffix=""
            [ $format = json ] && suffix="-json"
            echo "  compiled task --legacy-kb $kb --format $format: $(elapsed "$t2" "$t3") s (exit status $rc_task)"
            if [ $format = text ]; then
                python3 "$here/legacy_demos.py" "$d/original.out" "$d/task-$kb-$format.out" "$d/task-$kb-$format.err" |
                    sed 's/^/    against the original: /'
                [ "${PIPESTATUS[0]}" = 0 ] || status=1
            fi
            legacy_same "$d/ours-$kb$suffix" "$d/task-$kb-$format" | sed 's/^/    against run --legacy: /'
            [ "${PIPESTATUS[0]}" = 0 ] || status=1
            if [ "$rc" != "$rc_task" ]; then
                echo "    exit status: run --legacy $rc, compiled task $rc_task: DIFFER"
                status=1
            fi
            rm -rf "$d/run-$kb-$format" "$d/task-$kb-$format"
        done
    done
done
exit $status
