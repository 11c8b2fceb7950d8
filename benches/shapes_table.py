#!/usr/bin/env python3
"""Every workload of `shapes_prof` (issue 37) against the issue's targets, on one build.

Instructions a transition by callgrind: the difference of two runs of different lengths
over the difference of the transitions they print (docs/guide/performance.md, "Issue 37:
every shape workload on one build"). Three ways (compiled, interpreter, hand-written), the
two ratios (compiled / hand <= 10x, interpreter / compiled >= 10x) and, for the walks (d)
whose list length is a parameter, 256 places against 8 on both back ends (<= 2x).

    cargo build --profile bench -p sitlog-benches --example shapes_prof
    nice python3 benches/shapes_table.py            # every workload
    nice python3 benches/shapes_table.py d_room_walk c_pipe_pair   # some

One valgrind at a time (the machine's cores are shared). Prints a markdown table, then the
raw counts (workload, way, places, lengths, transitions, instructions) as comments.
"""

import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
# SHAPES_PROF: another build of the example (a copy kept while the tree is rebuilt).
BIN = os.environ.get("SHAPES_PROF") or os.path.join(
    HERE, "..", "target", "release", "examples", "shapes_prof")

# The lengths of the two runs, by way and places (rounds or calls). Long enough that the
# Prolog engine's start, which a workload with a user function pays once a run and which
# varies by some 5 * 10^5 instructions from run to run (its hash tables are seeded), moves a
# figure by no more than about 10 instructions a transition: with the lengths of the
# twentieth session (a tenth of these) `c_outarg_apply` read 704 compiled where the run
# itself costs 264 (performance.md, "the twenty-first session").
LENGTHS = {
    ("compiled", 8): (10000, 20000),
    ("interp", 8): (1000, 2000),
    ("hand", 8): (10000, 20000),
    ("compiled", 256): (1000, 2000),
    ("interp", 256): (100, 200),
    ("hand", 256): (1000, 2000),
}

# Walks whose list is a parameter of the run (256 places measured); the others keep a
# list of their own (`d_local_places`: 8 rooms of the DM, `d_const_ints`: 8 integers).
FIXED_LIST = {"d_local_places", "d_const_ints", "r17_d_prog_rooms"}


def all_workloads():
    """`ALL` of shapes_prof.rs, then the benches' own two."""
    src = open(os.path.join(HERE, "examples", "shapes_prof.rs")).read()
    block = re.search(r"const ALL: \[&str; \d+\] = \[(.*?)\];", src, re.S).group(1)
    return re.findall(r'"(\w+)"', block) + ["echo_calls", "list_search"]


def shape(name):
    return "d" if name.startswith(("d_", "r17_d_", "r18_d_", "r19_d_", "r22_d_", "r24_d_", "n24_d_", "n25_d_")) or name == "list_search" else "c"


def count(name, way, n, places):
    """(transitions, instructions) of one run under callgrind."""
    out = subprocess.run(
        ["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null", BIN,
         name, way, str(n), str(places)],
        cwd=HERE, capture_output=True, text=True, check=True)
    instr = int(re.search(r"Collected : (\d+)", out.stderr).group(1))
    return int(out.stdout.strip().splitlines()[-1]), instr


RAW = []


def per_transition(name, way, places):
    (n1, n2) = LENGTHS[(way, places)]
    t1, i1 = count(name, way, n1, places)
    t2, i2 = count(name, way, n2, places)
    RAW.append(f"{name} {way} {places} {n1}/{n2} transitions {t1}/{t2} instructions {i1}/{i2}")
    return (i2 - i1) / (t2 - t1)


def mark(ok):
    return "met" if ok else "**unmet**"


def main():
    names = sys.argv[1:] or all_workloads()
    if os.environ.get("NO_HEADER"):
        return rows(names)
    print("| workload | shape | compiled | interpreter | hand | compiled / hand (≤ 10×) "
          "| interp / compiled (≥ 10×) | 256 / 8 compiled (≤ 2×) | 256 / 8 interp (≤ 2×) "
          "| compiled / hand at 256 |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    rows(names)


def rows(names):
    for name in names:
        c, i, h = (per_transition(name, w, 8) for w in ("compiled", "interp", "hand"))
        row = [f"`{name}`", shape(name), f"{c:.1f}", f"{i:.1f}", f"{h:.1f}",
               f"{c / h:.1f}×: {mark(c / h <= 10)}", f"{i / c:.1f}×: {mark(i / c >= 10)}"]
        if shape(name) == "d" and name not in FIXED_LIST:
            c2, i2, h2 = (per_transition(name, w, 256) for w in ("compiled", "interp", "hand"))
            row += [f"{c2:.1f} = {c2 / c:.2f}×: {mark(c2 / c <= 2)}",
                    f"{i2:.1f} = {i2 / i:.2f}×: {mark(i2 / i <= 2)}",
                    f"{c2 / h2:.1f}×"]
        else:
            row += ["", "", ""]
        print("| " + " | ".join(row) + " |", flush=True)
    for r in RAW:
        print("<!-- " + r + " -->")


if __name__ == "__main__":
    main()
