#!/usr/bin/env python3
"""Negative controls of deck validation, for every problem executable.

    deck_rejections.py BIN_DIR PROBLEMS_DIR WORKDIR

For each problems/<name>/ holding <name>.toml (the problem's own deck), runs
BIN_DIR/<name> on that deck with one bad command-line override at a time:
  * an unknown key in a table of the problem's own (`<table>.no_such_key=1`);
  * a wrong type: a real-valued key of that table given a string;
  * an out-of-range value: the same key set below the lower bound that
    `<name> --help` declares for it (e.g. -1 for "> 0");
each both as a run and with --check. The key is chosen from `--help`, which
lists every key with its type and range: the first table of the deck, other
than [run] and [output], with a real key bounded below. Every case must exit
with the invalid-input code (2, docs/quickstart.md and src/io/problem_main.cpp),
name the offending key in its message, and write nothing: each runs in an
empty directory of its own, output.dir pointing inside it, which must stay
empty. Ends with 'N passed, M failed'; exits non-zero on failure.
"""
import os
import re
import shutil
import sys

try:
    import tomllib
except ImportError:  # Python < 3.11
    tomllib = None

from harness import Checks, run

BAD_INPUT = 2  # "2 invalid input" (docs/quickstart.md, the usage text of src/io/problem_main.cpp)
SKIP_TABLES = {"run", "output"}  # shared by every problem; the test wants the problem's own tables
KEY_LINE = re.compile(r"^  (\w+) \((real|integer|boolean|string|array of [a-z]+)\)(.*)$")
LOWER = re.compile(r"(>=|>) (-?[0-9.eE+-]+)")


def help_keys(exe, cwd):
    """{table: [(key, type, rest of the line)]} from `exe --help` (the 'deck keys:' part)."""
    p = run([exe, "--help"], expect=None, cwd=cwd)
    if p.returncode != 0 or "deck keys:" not in p.stdout:
        return None, p
    tables, table = {}, None
    for line in p.stdout.split("deck keys:", 1)[1].splitlines():
        m = re.match(r"^\[([\w.]+)\]\s*$", line)
        if m:
            table = m.group(1)
            tables.setdefault(table, [])
            continue
        m = KEY_LINE.match(line)
        if m and table:
            tables[table].append((m.group(1), m.group(2), m.group(3)))
    return tables, p


def deck_tables(deck):
    """Top-level tables named in the deck, in order."""
    with open(deck) as f:
        text = f.read()
    if tomllib is not None:
        return [k for k, v in tomllib.loads(text).items() if isinstance(v, dict)]
    return re.findall(r"^\[([\w.]+)\]\s*$", text, flags=re.M)


def pick(tables, in_deck):
    """(table, key, out-of-range value) for the first problem table of the deck with a real key bounded below."""
    order = [t for t in in_deck if t in tables and t not in SKIP_TABLES]
    order += [t for t in tables if t not in SKIP_TABLES and t not in order]
    for table in order:
        for key, typ, rest in tables[table]:
            if typ != "real":
                continue
            m = LOWER.search(rest)
            if m:
                bound = float(m.group(2))
                bad = bound - 1.0 if bound != 0 else -1.0
                return table, key, repr(bad)
    return None


def tree(path):
    """Everything under path (relative names), for the 'wrote nothing' check."""
    out = []
    for root, dirs, files in os.walk(path):
        out += [os.path.relpath(os.path.join(root, n), path) for n in dirs + files]
    return sorted(out)


def main():
    bin_dir, problems, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    checks = Checks()
    names = sorted(n for n in os.listdir(problems) if os.path.isfile(os.path.join(problems, n, n + ".toml")))
    checks.check(len(names) > 0, f"{len(names)} problems with their own deck under {problems}")
    for name in names:
        exe, deck = os.path.join(bin_dir, name), os.path.join(problems, name, name + ".toml")
        if not os.access(exe, os.X_OK):
            checks.check(False, f"{name}: no executable {exe}")
            continue
        scratch = os.path.join(work, name + "_help")
        os.makedirs(scratch)
        tables, p = help_keys(exe, scratch)
        if tables is None:
            checks.check(False, f"{name}: --help exits {p.returncode} without a 'deck keys:' list")
            continue
        choice = pick(tables, deck_tables(deck))
        in_deck = [t for t in deck_tables(deck) if t not in SKIP_TABLES]
        if choice is None or not in_deck:
            checks.check(False, f"{name}: no problem table in {deck} / no real key bounded below in --help")
            continue
        table, key, bad = choice
        unknown = f"{in_deck[0]}.no_such_key"
        cases = [
            ("unknown key", unknown, f"{unknown}=1", ["unknown key"]),
            ("wrong type", f"{table}.{key}", f'{table}.{key}="not a number"', ["expected real"]),
            ("out of range", f"{table}.{key}", f"{table}.{key}={bad}", ["out of range"]),
        ]
        for what, offending, override, phrases in cases:
            for mode in ([], ["--check"]):
                label = f"{name}{' --check' if mode else ''}: {what} ({override})"
                case_dir = os.path.join(work, re.sub(r"\W+", "_", f"{name}_{what}_{'check' if mode else 'run'}"))
                os.makedirs(case_dir)
                out_dir = os.path.join(case_dir, "out")
                p = run([exe, deck, override, f"output.dir={out_dir}", *mode], expect=None, cwd=case_dir)
                msg = p.stderr + p.stdout
                named = f"'{offending}'" in msg and all(s in msg for s in phrases)
                left = tree(case_dir)
                checks.check(p.returncode == BAD_INPUT and named and not left,
                             f"{label}: exit {p.returncode} (want {BAD_INPUT}), "
                             f"message {'names' if named else 'does not name'} '{offending}' "
                             f"({' / '.join(phrases)}), {'nothing written' if not left else 'wrote ' + ', '.join(left[:5])}"
                             + ("" if p.returncode == BAD_INPUT and named else f"\n    stderr: {p.stderr.strip()[-400:]}"))
        shutil.rmtree(scratch)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
