#!/usr/bin/env python3
"""The problems' own deck rules (a review of the problem executables):

    problem_rules.py BIN_DIR PROBLEMS_DIR WORKDIR

* decks whose analytic reference would not hold are refused (exit 2, the key
  named, nothing written): disc_pulse off a planar grid, without diffusion or
  with Sc != 1 (RBO24 eq. 38); fld_benchmarks' diffusion case off a planar
  grid (the planar heat kernel) and a negative Planck opacity; coag_kernels'
  product kernel at or past gelation (T = K0 N0 m0^2 t_end >= 1);
  coag_steady_state with its initial grains below the mass grid;
* dust sizes given as dust.sizes_from = "log" are read by disc_passive (it
  read past its arrays: the list stood empty) and disc_settling (refused):
  disc_passive's initial dust from log-spaced sizes equal to its listed ones
  agrees with the listed deck's to 1e-12.
Ends with 'N passed, M failed'; exits non-zero on failure.
"""
import os
import shutil
import sys

import numpy as np

from harness import Checks, run

bin_dir, problems, work = sys.argv[1], sys.argv[2], sys.argv[3]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
checks = Checks()


def refused(name, deck, overrides, key, label):
    out = os.path.join(work, label)
    p = run([os.path.join(bin_dir, name), os.path.join(problems, name, deck), f"output.dir={out}", *overrides],
            expect=None)
    text = p.stdout + p.stderr
    checks.check(p.returncode == 2 and key in text and not os.path.exists(out),
                 f"{name} {' '.join(overrides)}: exit {p.returncode} (2), names {key}, writes nothing")


refused("disc_pulse", "disc_pulse.toml", ['grid.geometry="cylindrical"'], "grid.geometry", "pulse_cyl")
refused("disc_pulse", "disc_pulse.toml", ["dust.diffusion=false"], "dust.diffusion", "pulse_nodiff")
refused("disc_pulse", "disc_pulse.toml", ["dust.schmidt=[2.0]"], "dust.schmidt", "pulse_sc")
refused("fld_benchmarks", "fld_diffusion.toml", ['grid.geometry="cylindrical"'], "grid.geometry", "fld_cyl")
refused("fld_benchmarks", "fld_equilibrium.toml", ["fld_test.kappa_planck=[-10.0, 3.0, 1.0, 0.3]"],
        "fld_test.kappa_planck", "fld_kappa")
refused("coag_kernels", "coag_kernels.toml", ['coagulation.kernel="product"'], "run.t_end", "coag_gel")
refused("coag_kernels", "coag_kernels.toml", ['coagulation.kernel="product"', "analytic.m0=2", "run.t_end=0.25"],
        "run.t_end", "coag_gel_m0")
refused("coag_steady_state", "coag_steady_state.toml", ["disc.a_init_max=1e-5"], "disc.a_init_max", "coag_small")
p = run([os.path.join(bin_dir, "coag_kernels"), os.path.join(problems, "coag_kernels", "coag_kernels.toml"),
         'coagulation.kernel="product"', "run.t_end=0.9", "--check"], expect=None)
checks.check(p.returncode == 0, f"coag_kernels product kernel at T = 0.9 is accepted (exit {p.returncode})")

log_sizes = ['dust.sizes_from="log"', "dust.sizes=[]", "dust.species=5", "dust.a_min=1e-5", "dust.a_max=0.1"]
p = run([os.path.join(bin_dir, "disc_settling"), os.path.join(problems, "disc_settling", "disc_settling_ci.toml"),
         'dust.sizes_from="log"', "dust.sizes=[]", "dust.species=2", "dust.a_min=1e-3", "dust.a_max=1e-2",
         "settling.dust_to_gas=[0.01, 0.01]", "--check"], expect=None)
checks.check(p.returncode == 0, f"disc_settling takes dust.sizes_from = \"log\" (exit {p.returncode})")

dirs = {}
for label, extra in (("list", []), ("log", log_sizes)):
    dirs[label] = os.path.join(work, f"passive_{label}")
    run([os.path.join(bin_dir, "disc_passive"), os.path.join(problems, "disc_passive", "disc_passive.toml"),
         f"output.dir={dirs[label]}", "run.max_steps=1", *extra], expect=0)
import h5py  # noqa: E402

with h5py.File(os.path.join(dirs["list"], "snapshot_00000.h5")) as a, \
        h5py.File(os.path.join(dirs["log"], "snapshot_00000.h5")) as b:
    worst, n = 0.0, 0
    for s in range(5):
        x, y = a[f"fields/dust_rho_{s}"][...], b[f"fields/dust_rho_{s}"][...]
        worst = max(worst, float(np.max(np.abs(x - y) / np.abs(x))))
        n += 1
checks.check(n == 5 and worst <= 1e-12, f"disc_passive: initial dust from log-spaced sizes equals the listed deck's "
                                        f"(5 species, worst relative difference {worst:.2e} <= 1e-12)")
sys.exit(checks.finish())
