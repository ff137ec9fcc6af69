#!/usr/bin/env python3
"""The full-size transition disc decks (RBO24 sec. 7: 150 x 150 cells, 100 and
135 species; isothermal and non-isothermal) get through their set-up and first
step on 2 MPI ranks as shipped: the deck is accepted, the dust, coagulation
and (non-isothermal) the temperature solver's first steady state (up to the
deck's temperature.steady_solves lagged solves, none on a fallback rung of
the linear solver) succeed, and the run stops at
run.max_steps = 1 with its checkpoint. A deck whose first steady state needs
more solves than it allows stops with exit code 3 at its first step: the
non-isothermal decks needed 38-40 against the default 30 (34 and 43 since the
FLD band floor and limiter change of 2026-12-06 (g)).

usage: transition_disc_full_decks.py EXE DECK_DIR WORKDIR MPIEXEC [ARGS ...]
"""
import os
import re
import shutil
import sys

from harness import Checks, files, run
import mote

exe, deck_dir, work, launcher = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
shutil.rmtree(work, ignore_errors=True)
checks = Checks()
for name in ("vfrag100", "vfrag1000", "nonisothermal_vfrag100", "nonisothermal_vfrag1000"):
    deck = os.path.join(deck_dir, f"transition_disc_{name}.toml")
    out = os.path.join(work, name)
    p = run(launcher + [exe, deck, "run.max_steps=1", "run.progress_interval=1000", f"output.dir={out}"], expect=None)
    checks.check(p.returncode == 0, f"{name}: exit code {p.returncode} after its first step")
    if p.returncode != 0:
        print(p.stdout[-3000:], p.stderr[-3000:])
        continue
    step = mote.last_snapshot(out).step
    checks.check(step == 1, f"{name}: its last snapshot is of step {step} (1)")
    checks.check(files(out, "checkpoint_") == ["checkpoint_00001.h5"], f"{name}: its checkpoint written at run.max_steps")
    if name.startswith("nonisothermal"):
        solves = re.search(r"temperature: steady state after (\d+) solves", p.stdout + p.stderr)
        fallbacks = (p.stdout + p.stderr).count("radiation: steady-state solve ")
        checks.check(solves is not None and fallbacks == 0, f"{name}: first steady state after "
                     f"{solves.group(1) if solves else '?'} lagged solves (the deck allows 80), "
                     f"{fallbacks} of them on a fallback rung")
sys.exit(checks.finish())
