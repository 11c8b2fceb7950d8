#!/usr/bin/env python3
"""Turn the original interpreter's JSON result into a golden expected.json.

    make_expected.py APP_DIR ORIGINAL.json > APP_DIR/expected.json

The original leaves the met expectation unbound in the history entries of
every situation it hands to a perceptual interpreter (semantics.md E1),
`neutral` ones included; our convention records it. This fills each such
slot, in history order (embedded histories included, depth first, which is
the order the entries were made):
  * `neutral` situation: `empty` (its only expectation; no input is read);
  * any other type: the next term of APP_DIR/script.txt, as SWI-Prolog's
    writeq prints it.
The script part is only right when every input term was met by an arc
(no "No satisfied expected intention" retries, semantics.md D-15, E3) and
the inputs are ground; the tool stops if terms are left over. Values that
a user function derived from the unbound slot (get_last_transition) are
not touched: fix them by hand. It also drops original_out_arg_unevaluated.
Needs swipl on PATH. Check the result by hand before committing it.
"""
import glob
import json
import os
import subprocess
import sys
import tempfile

HELPER = r"""
:- op(600, xfx, :), op(800, xfx, =>), op(850, xfx, =>>), op(900, xfx, ==>).
:- initialization(go, main).
read_all(File, Terms) :-
    setup_call_cleanup(open(File, read, In), read_terms(In, Terms), close(In)).
read_terms(In, Terms) :-
    read(In, T),
    ( T == end_of_file -> Terms = [] ; Terms = [T|Ts], read_terms(In, Ts) ).
go :-
    current_prolog_flag(argv, [Script|DmFiles]),
    maplist(read_all, DmFiles, Lists), append(Lists, All),
    include([T]>>(T = diag_mod(_, _, _)), All, Dms),
    read_all(Script, Inputs),
    forall(member(I, Inputs), (writeq(input(I)), nl)),
    read(user_input, Queries),
    forall(member(Dm-Sit, Queries), ( sit_type(Dms, Dm, Sit, Type), writeq(type(Type)), nl )).
sit_type(Dms, Dm, Sit, Type) :-
    functor(Dm, Name, _),
    member(diag_mod(Head, Sits, _), Dms), functor(Head, Name, _), !,
    member(S0, Sits), copy_term(S0, S), memberchk(id ==> Id, S), Id = Sit, !,
    ( memberchk(type ==> Type, S) -> true ; Type = none ).
sit_type(_, _, _, unknown).
"""


def dm_files(app):
    models = os.path.join(app, "models")
    if not os.path.exists(models):
        return sorted(glob.glob(os.path.join(app, "**", "*.dm"), recursive=True))
    out = subprocess.run(
        ["swipl", "-q", "-g", "read_term(T,[]),forall(member(X,T),(write(X),nl)),halt",
         "-t", "halt"],
        input="[" + ",".join(
            l.strip().rstrip(".") for l in open(models)
            if l.strip() and not l.strip().startswith("%")) + "].",
        capture_output=True, text=True, check=True).stdout
    return [os.path.join(app, p) for p in out.splitlines()]


def unbound(s):
    return s.startswith("_") and all(c.isalnum() or c == "_" for c in s)


def entries(items):
    for it in items:
        if isinstance(it, list):
            yield from entries(it)
        else:
            yield it


def main():
    app, orig_file = sys.argv[1], sys.argv[2]
    orig = json.load(open(orig_file))
    if orig.get("status") != "ok":
        sys.exit("make_expected: the original did not end with status ok")
    todo = [e for e in entries(orig["history"]) if unbound(e["expectation"])]
    with tempfile.NamedTemporaryFile("w", suffix=".pl", delete=False) as f:
        f.write(HELPER)
        helper = f.name
    query = "[" + ",".join("(%s)-(%s)" % (e["dm"], e["situation"]) for e in todo) + "].\n"
    out = subprocess.run(["swipl", "-q", helper, os.path.join(app, "script.txt")]
                         + dm_files(app), input=query, capture_output=True,
                         text=True, check=True).stdout.splitlines()
    os.unlink(helper)
    inputs = [l[len("input("):-1] for l in out if l.startswith("input(")]
    types = [l[len("type("):-1] for l in out if l.startswith("type(")]
    assert len(types) == len(todo), out
    for e, t in zip(todo, types):
        if t == "neutral":
            e["expectation"] = "empty"
        else:
            if not inputs:
                sys.exit("make_expected: more unbound expectations than script terms")
            e["expectation"] = inputs.pop(0)
    if inputs:
        sys.exit("make_expected: %d script term(s) left over (retries?)" % len(inputs))
    orig.pop("original_out_arg_unevaluated", None)
    json.dump(orig, sys.stdout, indent=2)
    sys.stdout.write("\n")


main()
