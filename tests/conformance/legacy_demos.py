#!/usr/bin/env python3
"""Compare one run of the original SitLog interpreter with one run of
`sitlogc run --legacy` on the same application and inputs; or (--same) a
run of `sitlogc run --legacy` with a run of the task `sitlogc build
--legacy` compiled from it.

usage: legacy_demos.py ORIGINAL_OUTPUT OUR_STDOUT OUR_STDERR
       legacy_demos.py --same RUN_STDOUT RUN_STDERR TASK_STDOUT TASK_STDERR

With --same the two runs must be identical: stdout (the history listing,
`Out Arg:`, the globals; or the `--format json` report) and stderr (what
the robot says and does, errors) line by line, variable names normalised
as above; the check's diagnostics that `sitlogc run` prints before the run
(W0203 for a DM defined twice; the task printed them when it was built)
are left out of the run's stderr. The first differing history entry (DM
and situation) and the first differing line of each stream are printed.

ORIGINAL_OUTPUT is the original's whole test-mode output (stdout and stderr);
OUR_STDOUT is sitlogc's report (the history listing) and OUR_STDERR its
test-mode rendering of the actions (`Golem says: ...`).

Compared: the number of transitions, the sequence of DMs and situations
(with the DM call depth), each transition's action, and the robot's
utterances in order. The original prints the expectation of a perceptual
situation unbound (defect E1 of shared/notes/semantics.md), so expectations
are not compared. Variable names are normalised (`_123`, `_G12` -> `_`).
Prints a summary and the first differences; exit status 1 if any."""
import json
import re
import sys

VAR = re.compile(r"\b_G?\d+\b|\b_[A-Z]\w*")


def split_top(text, seps):
    """Index of the first of `seps` at bracket depth 0 outside quotes."""
    depth = 0
    i = 0
    quote = None
    while i < len(text):
        c = text[i]
        if quote:
            if c == "\\":
                i += 2
                continue
            if c == quote:
                if i + 1 < len(text) and text[i + 1] == quote:
                    i += 2
                    continue
                quote = None
        elif c in "'\"`":
            quote = c
        elif c in "([{":
            if depth == 0 and any(text.startswith(s, i) for s in seps if s[0] in "([{"):
                return i
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif depth == 0:
            for s in seps:
                if text.startswith(s, i):
                    return i
        i += 1
    return -1


def transition(line):
    """(DM, situation, action) of `DM:(Situation,Expectation:Action)`."""
    i = split_top(line, [":("])
    if i < 0:
        return None
    dm = line[:i]
    body = line[i + 2:]
    if body.endswith(")"):
        body = body[:-1]
    j = split_top(body, [","])
    situation = body[:j] if j >= 0 else body
    rest = body[j + 1:] if j >= 0 else ""
    k = split_top(rest, [":"])
    action = rest[k + 1:] if k >= 0 else rest
    norm = lambda s: VAR.sub("_", s.strip())
    return norm(dm), norm(situation), norm(action)


def history(lines):
    """[(depth, dm, situation, action)] from a history listing; `[`/`]`
    (quoted or not) open and close an embedded DM."""
    out = []
    depth = 0
    for raw in lines:
        line = raw.strip()
        if not line:
            continue
        if line in ("[", "'['"):
            depth += 1
            continue
        if line in ("]", "']'"):
            depth -= 1
            continue
        t = transition(line)
        if t:
            out.append((depth,) + t)
    return out


def section(lines, start, end):
    got = []
    inside = False
    for line in lines:
        s = line.rstrip("\n")
        if not inside:
            if s.strip() == start:
                inside = True
            continue
        if s.strip().startswith(end):
            break
        got.append(s)
    return got


def original_utterances(lines):
    p = "'Golem says: '"
    out = []
    for line in lines:
        i = line.find(p)
        if i < 0:
            continue
        m = line[i + len(p):].rstrip("\n")
        if len(m) >= 2 and m[0] == "'" and m[-1] == "'":
            m = m[1:-1].replace("''", "'").replace("\\'", "'").replace("\\\\", "\\")
        out.append(m)
    return out


def our_utterances(lines):
    p = "Golem says: "
    return [l.rstrip("\n")[len(p):] for l in lines if l.startswith(p)]


def first_differences(name, a, b, limit=5):
    diffs = []
    for i, (x, y) in enumerate(zip(a, b)):
        if x != y:
            diffs.append(f"  {name} #{i + 1}:\n    original: {x}\n    sitlogc:  {y}")
            if len(diffs) >= limit:
                break
    if len(a) != len(b) and len(diffs) < limit:
        n = min(len(a), len(b))
        extra = a[n:n + 1] or b[n:n + 1]
        who = "original" if len(a) > len(b) else "sitlogc"
        diffs.append(f"  {name}: {who} has more from #{n + 1}: {extra[0]}")
    return diffs


DIAGNOSTIC = re.compile(r"^\[[EW]\d{4}\] ")
DIAGNOSTIC_END = re.compile(r"^─*╯\s*$")


def without_diagnostics(lines):
    """`lines` without the check's diagnostics at their start (each from
    `[W0203] Warning: ...` to its closing `───╯`)."""
    i = 0
    while i < len(lines) and DIAGNOSTIC.match(lines[i]):
        j = i + 1
        while j < len(lines) and not DIAGNOSTIC_END.match(lines[j]) and not DIAGNOSTIC.match(lines[j]):
            j += 1
        i = j + 1 if j < len(lines) and DIAGNOSTIC_END.match(lines[j]) else j
    return lines[i:]


def json_history(lines):
    """[(0, dm, situation, action)] of a `--format json` report."""
    try:
        report = json.loads("".join(lines))
    except ValueError:
        return []
    norm = lambda s: VAR.sub("_", str(s))
    out = []

    def walk(entries, depth):
        for h in entries:
            if isinstance(h, list):
                walk(h, depth + 1)
            elif isinstance(h, dict):
                out.append((depth, norm(h.get("dm")), norm(h.get("situation")), norm(h.get("action"))))

    walk(report.get("history") or [], 0)
    return out


def same(paths):
    """--same: the interpreter's run against the compiled task's."""
    read = lambda p: open(p, encoding="utf-8", errors="replace").readlines()
    run_out, run_err, task_out, task_err = map(read, paths)
    run_err = without_diagnostics(run_err)
    norm = lambda lines: [VAR.sub("_", l.rstrip("\n")) for l in lines]
    diffs = []
    hr = history(section(run_out, "Execution history:", "Out Arg:")) or json_history(run_out)
    ht = history(section(task_out, "Execution history:", "Out Arg:")) or json_history(task_out)
    for i, (a, b) in enumerate(zip(hr, ht)):
        if a != b:
            diffs.append(
                f"  first differing history entry #{i + 1}:\n"
                f"    run:  {a[1]}:({a[2]}, ...: {a[3]}) (depth {a[0]})\n"
                f"    task: {b[1]}:({b[2]}, ...: {b[3]}) (depth {b[0]})"
            )
            break
    else:
        if len(hr) != len(ht):
            n = min(len(hr), len(ht))
            who, extra = ("run", hr[n]) if len(hr) > len(ht) else ("task", ht[n])
            diffs.append(f"  history: the {who} has more from #{n + 1}: {extra[1]}:({extra[2]}, ...)")
    for name, a, b in (("stdout", run_out, task_out), ("stderr", run_err, task_err)):
        a, b = norm(a), norm(b)
        for i, (x, y) in enumerate(zip(a, b)):
            if x != y:
                diffs.append(f"  {name} line {i + 1}:\n    run:  {x}\n    task: {y}")
                break
        else:
            if len(a) != len(b):
                n = min(len(a), len(b))
                who, extra = ("run", a[n]) if len(a) > len(b) else ("task", b[n])
                diffs.append(f"  {name}: the {who} has more from line {n + 1}: {extra}")
    print(
        f"run --legacy and the compiled task: transitions {len(hr)} / {len(ht)}; "
        f"stdout {len(run_out)} / {len(task_out)} lines, stderr {len(run_err)} / {len(task_err)} lines"
    )
    for d in diffs:
        print(d)
    print("identical" if not diffs else "DIFFER")
    return 1 if diffs else 0


def main():
    if len(sys.argv) == 6 and sys.argv[1] == "--same":
        return same(sys.argv[2:])
    if len(sys.argv) != 4:
        print(__doc__.split("\n\n")[1])
        return 2
    read = lambda p: open(p, encoding="utf-8", errors="replace").readlines()
    orig = read(sys.argv[1])
    ours_out = read(sys.argv[2])
    ours_err = read(sys.argv[3])
    ho = history(section(orig, "'Execution history: '", "'Dialogue manager ends'"))
    hs = history(section(ours_out, "Execution history:", "Out Arg:"))
    uo = original_utterances(orig)
    us = our_utterances(ours_err)
    seq = lambda h: [(d, dm, s) for d, dm, s, _ in h]
    acts = lambda h: [a for _, _, _, a in h]
    diffs = []
    diffs += first_differences("DM/situation", seq(ho), seq(hs))
    diffs += first_differences("action", acts(ho), acts(hs))
    diffs += first_differences("utterance", uo, us)
    print(
        f"transitions: original {len(ho)}, sitlogc {len(hs)}; "
        f"utterances: original {len(uo)}, sitlogc {len(us)}"
    )
    if not ho:
        diffs.insert(0, "  the original's output has no execution history")
    for d in diffs:
        print(d)
    print("agree" if not diffs else "DIFFER")
    return 1 if diffs else 0


if __name__ == "__main__":
    sys.exit(main())
