#!/usr/bin/env python3
"""Rules that only the set-up can judge (the rank count, derived values) fail as bad input before any output.

    setup_rules.py BIN_DIR PROBLEMS_DIR WORKDIR LAUNCHER...

--check validates the deck without the set-up, so it cannot see rules on the
number of MPI ranks (docs/quickstart.md). This test runs every problem's own
deck (problems/<name>/<name>.toml) on 2 ranks for one step (run.max_steps=1),
and set-ups that break a rank rule on purpose (too few radial cells per rank):
  * each run either steps (exit 0) or is refused with the bad-input code 2, one
    error line and no output directory; never exit 1 (a std::invalid_argument of a
    module's set-up was exit 1, e.g. disc_irradiation's FLD solver on 2 ranks), and
    never a hang (a rule broken on one rank only stopped that rank alone: grid.nr = 3);
  * --check of a deck that a run on 2 ranks refuses exits 0 and writes nothing (the
    documented limit of --check).
Ends with 'N passed, M failed'.
"""
import glob
import os
import shutil
import sys

from harness import MPI_ENV, Checks, run_within

BAD_INPUT = 2  # docs/quickstart.md, include/mote/core/exit_codes.hpp

bin_dir, problems, work, launcher = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
checks = Checks()

# Decks that break a rank rule on 2 ranks: (problem, overrides, message).
RANK_RULES = [
    ("disc_pulse", ["grid.nr=3"], "grid.nr = 3 gives ranks fewer than"),
]


def run_on_two_ranks(exe, args):
    """(exit code, output); exit code None for a run killed after 120 s (a rank waiting for one that stopped)."""
    return run_within([*launcher, exe, *args], 120, cwd=work, env=dict(os.environ, **MPI_ENV))


def refused_or_runs(label, exe, args, out, message=None):
    """A 2-rank run of one step: exit 0, or exit 2 with one error line (holding `message`) and no `out`.
    Returns the exit code."""
    rc, text = run_on_two_ranks(exe, [*args, f"output.dir={out}", "run.max_steps=1"])
    errors = [line for line in text.splitlines() if "error: " in line]
    if message is not None:
        checks.check(rc == BAD_INPUT and message in text, f"{label}: refused on 2 ranks (exit {rc}) naming "
                     f"{message!r}" + ("" if rc == BAD_INPUT and message in text else f"\n{text[-2000:]}"))
    else:
        checks.check(rc in (0, BAD_INPUT), f"{label}: on 2 ranks exit {rc} is 0 or 2" +
                     ("" if rc in (0, BAD_INPUT) else f"\n{text[-2000:]}"))
    if rc == BAD_INPUT:
        checks.check(len(errors) == 1, f"{label}: one error line ({errors})")
        checks.check(not os.path.exists(out), f"{label}: no output directory")
    return rc


def check_passes(label, exe, args, out):
    """--check on 2 ranks accepts a deck whose run the set-up refuses, and writes nothing."""
    rc, text = run_on_two_ranks(exe, [*args, f"output.dir={out}", "--check"])
    checks.check(rc == 0 and not os.path.exists(out), f"{label}: --check on 2 ranks exits {rc} == 0 (it cannot "
                 "see rank rules) and writes nothing")


def main():
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    decks = sorted(d for d in glob.glob(os.path.join(problems, "*", "*.toml"))
                   if os.path.basename(d) == os.path.basename(os.path.dirname(d)) + ".toml")
    refused = 0
    for deck in decks:
        name = os.path.basename(os.path.dirname(deck))
        exe, out = os.path.join(bin_dir, name), os.path.join(work, name)
        if refused_or_runs(name, exe, [deck], out) == BAD_INPUT:
            refused += 1
            check_passes(name, exe, [deck], out + "_check")
        shutil.rmtree(out, ignore_errors=True)
    checks.check(refused > 0, f"{refused} of {len(decks)} problems refuse 2 ranks")
    for name, overrides, message in RANK_RULES:
        exe, deck = os.path.join(bin_dir, name), os.path.join(problems, name, name + ".toml")
        label, out = f"{name} {' '.join(overrides)}", os.path.join(work, name + "_rule")
        refused_or_runs(label, exe, [deck, *overrides], out, message)
        check_passes(label, exe, [deck, *overrides], out + "_check")
    shutil.rmtree(work, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
