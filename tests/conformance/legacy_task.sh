# shellcheck shell=bash
# What legacy_demos.sh and legacy_apps.sh share for the compiled tasks
# (sourced after original_legacy_setup, which sets `sitlogc` and `work`):
#
#   legacy_task APP
#       prints the path of the task `sitlogc build APP --legacy` compiles
#       from $SITLOG_HOME/APP (APP as `apps/NAME`), built once per APP into
#       $LEGACY_TASKS (default $work/tasks; a build takes minutes: set
#       SITLOGC_CACHE_DIR to share sitlogc build's cache between runs, and
#       LEGACY_TASKS to keep the tasks, named `apps.NAME`: one found there
#       is used as it is); on failure prints why on stderr (the build log's
#       end) and returns 1.
#   legacy_same RUN TASK
#       compares RUN.out/RUN.err (`sitlogc run --legacy`) with
#       TASK.out/TASK.err (the compiled task) with legacy_demos.py --same.

legacy_task() {
    local dir=${LEGACY_TASKS:-$work/tasks}
    local t="$dir/${1//\//.}"
    mkdir -p "$dir"
    if [ ! -x "$t" ]; then
        if ! "$sitlogc" build "$SITLOG_HOME/$1" --legacy -o "$t" >"$t.build.log" 2>&1; then
            echo "sitlogc build $SITLOG_HOME/$1 --legacy failed:" >&2
            tail -n 5 "$t.build.log" | sed 's/^/    /' >&2
            return 1
        fi
    fi
    echo "$t"
}

legacy_same() {
    python3 "$here/legacy_demos.py" --same "$1.out" "$1.err" "$2.out" "$2.err"
}
