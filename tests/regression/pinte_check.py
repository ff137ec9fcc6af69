#!/usr/bin/env python3
"""The Pinte et al. (2009) benchmark of RBO24 sec. 4.3 (VALIDATION D5) through
problems/disc_passive/check.py.

usage: pinte_check.py EXE WORKDIR ci|full

ci:   pinte_low.toml and pinte_high.toml on a 60 x 40 grid (10 inner cells)
      with their 20 bands: energy balance, dust mass, the optically thin top
      row, the super-heated layer.
full: both decks at their resolution and at 1.5x it, two runs at a time:
      every check of check.py with --compare, and the figure in the style of
      RBO24 Fig. 9 (WORKDIR/pinte.png).
"""
import os
import shutil
import subprocess
import sys

from harness import Checks, run

HERE = os.path.dirname(os.path.abspath(__file__))
PROBLEM = os.path.join(HERE, "..", "..", "problems", "disc_passive")
sys.path.insert(0, PROBLEM)
import check as passive  # noqa: E402

exe, work, mode = sys.argv[1], sys.argv[2], sys.argv[3]
checks = Checks()
# The steady state's energy balance, held here to 1e-6 (VALIDATION D5 and check.py
# allow 1e-3; measured 6.7e-10 to 8e-8 on these decks): the regression the c r
# cap on the FLD coefficient removed showed 3e-5, which 1e-3 would let through.
BALANCE = 1e-6
MASSES = {"low": 1e-2, "high": 10.0}
FINE = {"low": ["grid.nr=360", "grid.r_block_cells=60", "grid.ntheta=225"],
        "high": ["grid.nr=444", "grid.r_block_cells=144", "grid.ntheta=225"]}


def fresh(name):
    path = os.path.join(work, name)
    shutil.rmtree(path, ignore_errors=True)
    return path


def deck(name):
    """The deck and its opacity table, wherever ctest runs."""
    return [os.path.join(PROBLEM, f"pinte_{name}.toml"),
            "radiation.opacity_file=" + os.path.join(PROBLEM, "pinte_opacities.dat")]


def run_together(commands):
    """Runs the commands at once and waits for all; raises if any exits non-zero."""
    procs = [subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True) for cmd in commands]
    for cmd, p in zip(commands, procs):
        out = p.communicate()[0]
        if p.returncode != 0:
            raise AssertionError(f"{' '.join(cmd)} exited {p.returncode}\n{out[-3000:]}")


def check_run(name, run_dir, fine_dir=None, ci_thin=None):
    out = passive.analyse(run_dir, fine_dir)
    passive.pinte_checks(run_dir, out)
    mass = MASSES[name]
    checks.check(abs(out["energy_balance"]) <= BALANCE,
                 f"{name}: energy balance {out['energy_balance']:.3e} (|.| <= {BALANCE:g})")
    checks.check(abs(out["dust_mass_earth"] / mass - 1.0) <= passive.MASS,
                 f"{name}: dust mass {out['dust_mass_earth']:.4e} M_earth against {mass:g} (|ratio - 1| <= {passive.MASS:g})")
    checks.check(abs(out["thin_worst"]) <= passive.THIN_LIMIT,
                 f"{name}: top row T / T_thin - 1 = {out['thin_worst']:.3e} at worst, median {out['thin_median']:.3e} "
                 f"(|.| <= {passive.THIN_LIMIT:g})")
    checks.check(out["superheating_min"] >= passive.SUPERHEATING,
                 f"{name}: super-heated layer, min over R >= {passive.RIM:g} R_in of T_max / T_mid = "
                 f"{out['superheating_min']:.2f} (>= {passive.SUPERHEATING:g})")
    if ci_thin is not None:
        checks.check(abs(out["thin_worst"]) <= ci_thin,
                     f"{name}: top row T / T_thin - 1 = {out['thin_worst']:.3e} at worst on the CI grid "
                     f"(|.| <= {ci_thin:g}: its measured -5.2e-4 with a 4x margin)")
    print(f"INFO {name}: mid-plane optical depth at 0.81 um {out['tau_081']:.3g}, "
          f"{out['fld_iterations']} BiCGStab iterations")
    if fine_dir:
        checks.check(out["mid_change"] < passive.CONVERGENCE and out["top_change"] < passive.CONVERGENCE,
                     f"{name}: 1.5x resolution, R >= {passive.RIM:g} R_in: mid-plane {out['mid_change']:.3e}, top "
                     f"{out['top_change']:.3e} (< {passive.CONVERGENCE:g}); inner rim {out['rim_change']:.3e}")


if mode == "ci":
    coarse = fresh("low_coarse")
    run([exe, *deck("low"), f"output.dir={coarse}", "grid.nr=60", "grid.r_block_cells=10", "grid.ntheta=40"])
    check_run("low", coarse, ci_thin=2e-3)
    # The high-mass disc solved on the same grid (3 s). The 1.5x-resolution rows stay in the full
    # mode: on these grids the mid-plane still moves by 4.6 % (low mass, 60 x 40 against 90 x 60).
    high = fresh("high_coarse")
    run([exe, *deck("high"), f"output.dir={high}", "grid.nr=60", "grid.r_block_cells=10", "grid.ntheta=40"])
    check_run("high", high, ci_thin=2e-3)
else:
    runs = {name: (fresh(name), fresh(f"{name}_fine")) for name in ("low", "high")}
    # Two at a time (each run is one process on one core): the two decks, then their 1.5x grids.
    run_together([[exe, *deck(name), f"output.dir={runs[name][0]}"] for name in runs])
    run_together([[exe, *deck(name), f"output.dir={runs[name][1]}"] + FINE[name] for name in runs])
    for name, (base, fine) in runs.items():
        check_run(name, base, fine)
    subprocess.run([sys.executable, os.path.join(PROBLEM, "plot_pinte.py"), runs["low"][0], runs["high"][0], "--fine",
                    runs["low"][1], runs["high"][1], "--out", os.path.join(work, "pinte.png")], check=True)
sys.exit(checks.finish())
