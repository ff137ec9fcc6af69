#!/usr/bin/env python3
"""Every deck shipped in problems/<name>/ is accepted by its executable.

    decks_valid.py BIN_DIR PROBLEMS_DIR WORKDIR

Runs `BIN_DIR/<name> DECK --check` in WORKDIR for each problems/<name>/*.toml:
exit code 0, the resolved deck printed, and nothing written (a check allocates
and writes nothing). Decks run from the repository root and name their input
files from there (problems/disc_passive/pinte_opacities.dat): WORKDIR holds a
link `problems` to PROBLEMS_DIR so that they resolve the same. Catches decks left behind by a renamed or removed key.
Then shipped decks with overrides that break cross-key rules (R_out < R_in,
theta inverted, array lengths, a choice the problem needs): --check must exit 2
and report every broken rule with the file and line (or override) of its key.
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
    os.symlink(os.path.abspath(problems), os.path.join(work, "problems"))
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
    check_rejections(checks, bin_dir, problems, work)
    checks.check(os.listdir(work) == ["problems"], "--check wrote nothing")
    return checks.finish()


# Decks that break rules tying several keys together: --check must apply every
# rule the run applies, and report all broken ones, each with where its key was set.
CROSS_KEY_CASES = [
    ("disc_pulse", ["grid.R_in=60", "grid.theta_max=-0.6", "dust.sizes=[1.0, 2.0]"],
     ["(3 errors)",
      "disc_pulse.toml:17: key 'grid.R_out': must exceed grid.R_in = 60.0 (command line 'grid.R_in=60')",
      "command line 'grid.theta_max=-0.6': key 'grid.theta_max': must exceed grid.theta_min = -0.523598775598",
      "command line 'dust.sizes=[1.0, 2.0]': key 'dust.sizes': disc_pulse evolves one dust species"]),
    ("sph_dustywave", ["dust.species=3", "dust.K=[1.0, 2.0]", "dust.eps=[0.1]", "sph.eos=isothermal"],
     ["(3 errors)", "key 'dust.K': needs 1 or 3 entries (dust.species = 3 (command line 'dust.species=3')), got 2",
      "key 'dust.pdv': \"gas\" needs sph.eos = \"isothermal\" (command line 'sph.eos=isothermal') to be",
      "command line 'sph.eos=isothermal': key 'sph.eos': sph_dustywave needs \"adiabatic\""]),
    ("sph_dustybox", ["dust.species=17"],
     ["(1 error)", "command line 'dust.species=17': key 'dust.species': two-fluid dust couples at most 16 species, "
                   "got 17"]),
    ("viscous_ring", ["gas.Sigma_index=0.5", "gas.R_c=20"],
     ["(2 errors)", "command line 'gas.R_c=20': key 'gas.R_c': viscous_ring needs it equal to gas.R_ref = 10.0 (",
      "key 'gas.Sigma_index': viscous_ring needs it equal to"]),
]


def check_rejections(checks, bin_dir, problems, work):
    for name, overrides, expected in CROSS_KEY_CASES:
        deck = os.path.join(problems, name, name + ".toml")
        p = run([os.path.join(bin_dir, name), deck, "--check"] + overrides, expect=None, cwd=work)
        checks.check(p.returncode == 2, f"{name} --check {' '.join(overrides)}: exit {p.returncode} == 2")
        for e in expected:
            checks.check(e in p.stderr, f"{name} --check: reports {e!r}" + ("" if e in p.stderr else "\n" + p.stderr))


if __name__ == "__main__":
    sys.exit(main())
