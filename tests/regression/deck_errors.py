#!/usr/bin/env python3
"""Bad input is rejected before any output exists (foundation acceptance 2).

usage: deck_errors.py EXE WORKDIR
Each bad deck must exit with code 2, name the offending key or file in its
message, and leave no output directory behind.
"""
import os
import shutil
import sys

from harness import Checks, run

exe, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
checks = Checks()

GOOD = """[run]
t_end = 0.01
[output]
dir = "{out}"
[grid]
nx = 16
ny = 16
[transport]
diffusivity = 0.01
[pulse]
t0 = 0.5
"""

cases = {
    "unknown_key": (GOOD.replace("nx = 16", "nxx = 16"), ["unknown key 'grid.nxx'", "did you mean 'grid.nx'", ".toml:6:"]),
    "wrong_type": (GOOD.replace("nx = 16", 'nx = "sixteen"'), ["key 'grid.nx'", "expected integer", ".toml:6:"]),
    "negative_resolution": (GOOD.replace("ny = 16", "ny = -16"), ["key 'grid.ny'", "out of range", ">= 4"]),
    "missing_required": (GOOD.replace("diffusivity = 0.01", ""), ["missing required key 'transport.diffusivity'"]),
    "syntax_error": (GOOD.replace("[grid]", "[grid"), ["TOML syntax error"]),
    "bad_choice": (GOOD + "[scheme]\nlimiter = \"superbee\"\n", ["key 'scheme.limiter'", "one of \"none\", \"vanleer\", \"mc\""]),
    # Every output file stores the resolved deck in one HDF5 attribute (at most 65000 bytes).
    "deck_too_long": (GOOD.replace('dir = "{out}"', 'dir = "{out}"\nsnapshot_times = ['
                                   + ", ".join(repr(1.1e-6 * k) for k in range(1, 6001)) + "]"),
                      ["the resolved deck takes", "bytes; snapshots and checkpoints store it in one attribute of at most 65000"]),
}
for name, (text, expected) in cases.items():
    out = os.path.join(work, "out_" + name)
    deck = os.path.join(work, name + ".toml")
    with open(deck, "w") as f:
        f.write(text.format(out=out))
    p = run([exe, deck], expect=None)
    msg = p.stderr
    checks.check(p.returncode == 2, f"{name}: exit code {p.returncode} == 2")
    for e in expected:
        checks.check(e in msg and deck in msg, f"{name}: message names the deck and contains {e!r}")
    checks.check(not os.path.exists(out), f"{name}: no output directory created")

# Unreadable deck file and a bad command-line override.
out = os.path.join(work, "out_override")
good = os.path.join(work, "good.toml")
with open(good, "w") as f:
    f.write(GOOD.format(out=out))
p = run([exe, os.path.join(work, "does_not_exist.toml")], expect=None)
checks.check(p.returncode == 2 and "cannot read deck file" in p.stderr and "does_not_exist.toml" in p.stderr,
             "missing deck file: exit 2 and the file is named")
p = run([exe, good, "grid.nx=0"], expect=None)
checks.check(p.returncode == 2 and "command line 'grid.nx=0'" in p.stderr, "bad override: exit 2 and named")
checks.check(not os.path.exists(out), "bad override: no output directory created")
# Inconsistent values found by the problem itself are reported the same way.
p = run([exe, good, "grid.x_max=-1"], expect=None)
checks.check(p.returncode == 2 and "x_max" in p.stderr and not os.path.exists(out), "inconsistent grid: exit 2, no output")
# Command lines and output directories refused before any work (exit 2), each naming what is wrong.
a_file = os.path.join(work, "a_file")
with open(a_file, "w") as f:
    f.write("not a directory\n")
command_lines = {
    "--restart before another flag": ([good, "--restart", "--check"], "--restart needs a checkpoint file or 'latest'"),
    "--restart twice": ([good, "--restart", "a.h5", "--restart", "b.h5"], "--restart given twice ('a.h5' and 'b.h5')"),
    "--restart latest without a deck": (["--restart", "latest"], "--restart latest needs the deck"),
    "empty output.dir": ([good, "output.dir="], "key 'output.dir': must name a directory (it is empty)"),
    "output.dir a file": ([good, f"output.dir={a_file}"], f"key 'output.dir': '{a_file}' exists and is not a directory"),
    "output.dir inside a file": ([good, f"output.dir={a_file}/run"],
                                 f"key 'output.dir': '{a_file}' exists and is not a directory"),
    "a number beyond double": ([good, "run.t_end=1e400"], "key 'run.t_end': '1e400' is not a TOML value"),
}
for name, (args, expected) in command_lines.items():
    for check_only in ([], ["--check"]):
        if check_only and "--check" in args:
            continue
        p = run([exe, *args, *check_only], expect=None, cwd=work)
        checks.check(p.returncode == 2 and expected in p.stderr,
                     f"{name}{' (--check)' if check_only else ''}: exit {p.returncode} == 2, message {expected!r}" +
                     ("" if expected in p.stderr else f"\n{p.stderr[-1500:]}"))
checks.check(not os.path.exists(out) and sorted(os.listdir(work)) == sorted(
    [n + ".toml" for n in cases] + ["good.toml", "a_file"]), "refused command lines: nothing written")
# A key set twice on the command line: the last applies, with a warning (scripts add particular
# overrides after common ones).
p = run([exe, good, "grid.nx=8", "grid.nx=12", "--check"], expect=None, cwd=work)
expected = "key 'grid.nx' set twice on the command line: 'grid.nx=12' applies, not 'grid.nx=8'"
checks.check(p.returncode == 0 and expected in p.stderr and "nx = 12" in p.stdout,
             f"a key set twice: the last applies, with the warning {expected!r}")
# The good deck runs.
run([exe, good])
checks.check(os.path.exists(os.path.join(out, "snapshot_00001.h5")), "good deck: runs and writes snapshots")
p = run([exe, "--help"])
checks.check("diffusivity (real)  required" in p.stdout, "--help lists the keys with types and defaults")
sys.exit(checks.finish())
