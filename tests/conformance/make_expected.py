#!/usr/bin/env python3
"""Turn the original interpreter's JSON result into a golden expected.json.

    make_expected.py ORIGINAL.json SCRIPT.txt > expected.json

The original leaves the met expectation of perceptual situations unbound
(semantics.md E1); our convention records it. This fills each unbound
expectation slot, in history order (embedded histories included, depth
first, which is the order the entries were made), with the next term of the
script, as SWI-Prolog writeq prints it. That is only right when every input
term was met by an arc (no "No satisfied expected intention" retries) and
the inputs are ground: check the result by hand. It also drops the
original_out_arg_unevaluated key. Values that a user function derived from
the unbound slot (e.g. get_last_transition) must still be fixed by hand.
"""
import json
import subprocess
import sys

NORMALISE = r"""
:- op(600, xfx, :), op(800, xfx, =>), op(850, xfx, =>>), op(900, xfx, ==>).
go :- read(T), ( T == end_of_file -> true ; writeq(T), nl, go ).
:- initialization((go, halt), main).
"""


def script_terms(path):
    with open(path) as f:
        text = f.read()
    prog = "/tmp/make_expected_norm.pl"
    with open(prog, "w") as f:
        f.write(NORMALISE)
    out = subprocess.run(["swipl", "-q", prog], input=text, capture_output=True,
                         text=True, check=True).stdout
    return out.splitlines()


def is_unbound(s):
    return s.startswith("_") and all(c.isalnum() or c == "_" for c in s)


def fill(items, inputs):
    for it in items:
        if isinstance(it, list):
            fill(it, inputs)
        elif is_unbound(it["expectation"]):
            if not inputs:
                sys.exit("make_expected: more unbound expectations than script terms")
            it["expectation"] = inputs.pop(0)


def main():
    orig = json.load(open(sys.argv[1]))
    inputs = script_terms(sys.argv[2])
    if orig.get("status") != "ok":
        sys.exit("make_expected: the original did not end with status ok")
    fill(orig["history"], inputs)
    if inputs:
        sys.exit("make_expected: %d script term(s) left over (retries?)" % len(inputs))
    orig.pop("original_out_arg_unevaluated", None)
    json.dump(orig, sys.stdout, indent=2)
    sys.stdout.write("\n")


main()
