#!/usr/bin/env python3
"""Every deck shipped in problems/<name>/ is accepted by its executable.

    decks_valid.py BIN_DIR PROBLEMS_DIR WORKDIR

Runs `BIN_DIR/<name> DECK --check` in WORKDIR for each problems/<name>/*.toml:
exit code 0, the resolved deck printed, and nothing written (a check allocates
and writes nothing). Catches decks left behind by a renamed or removed key.
"""
import glob
import os
import shutil
import sys

from harness import Checks, run


def main():
    bin_dir, problems, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    checks = Checks()
    decks = sorted(glob.glob(os.path.join(problems, "*", "*.toml")))
    checks.check(len(decks) > 0, f"{len(decks)} decks found under {problems}")
    for deck in decks:
        name = os.path.basename(os.path.dirname(deck))
        exe = os.path.join(bin_dir, name)
        label = os.path.relpath(deck, problems)
        if not os.path.exists(exe):
            checks.check(False, f"{label}: no executable {name} in {bin_dir}")
            continue
        p = run([exe, deck, "--check"], expect=None, cwd=work)
        checks.check(p.returncode == 0 and "# resolved deck" in p.stdout,
                     f"{label}: {name} --check exits {p.returncode}"
                     + ("" if p.returncode == 0 else f" ({p.stderr.strip()[-300:]})"))
    checks.check(os.listdir(work) == [], "--check wrote nothing")
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
