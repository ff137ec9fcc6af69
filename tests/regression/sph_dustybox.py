#!/usr/bin/env python3
"""sph_dustybox end to end (LAB15 sec. 3, VALIDATION B1, B3): the deck runs
with the engine's time-step (the gas Courant condition, dt = 0.011) and
t_s = 0.1, 1e-3 and 1e-5 (dt / t_s = 0.1, 11 and 1100), at eps = 0.01 and 1,
with the improved drag (LAB15 eq. 17-19): check.py finds the dust velocity
within 1e-3 of eq. 31 and the momentum budget exact to 1e-12; the original
scheme (eq. 4-6) at dt / t_s = 11 has its error reported; one figure of both.
B2 (VALIDATION: 20^3 particles per phase on cubic lattices in [-2, 2)^3, the
dust lattice shifted by half a spacing, SPH-summed densities): the same t_s
and eps at dt = 0.05 (dt / t_s = 0.5 to 5000), asserted at 1e-3 (VALIDATION:
2 %). Two species in 1D against the exact solution of the linear system (see below).

usage: sph_dustybox.py EXE WORKDIR
"""
import os
import shutil
import sys

from harness import ROOT, Checks, run

exe, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)
pdir = os.path.join(ROOT, "problems", "sph_dustybox")
deck = os.path.join(pdir, "sph_dustybox.toml")
checks = Checks()
check = ["/usr/bin/python3", os.path.join(pdir, "check.py")]
for eps in (0.01, 1.0):
    for ts in (0.1, 1e-3, 1e-5):
        out = os.path.join(work, f"eps{eps:g}_ts{ts:g}")
        run([exe, deck, f"output.dir={out}", f"dust.stopping_time=[{ts!r}]", f"dustybox.eps={eps!r}"])
        c = run(check + [out, "--ts", repr(ts), "--eps", repr(eps), "--max-error", "1e-3"], expect=None)
        print(c.stdout.strip())
        checks.check(c.returncode == 0, f"improved drag, eps = {eps:g}, t_s = {ts:g}: v_D against eq. 31")
for eps in (0.01, 1.0):
    for ts in (0.1, 1e-3, 1e-5):
        out = os.path.join(work, f"b2_eps{eps:g}_ts{ts:g}")
        run([exe, deck, f"output.dir={out}", f"dust.stopping_time=[{ts!r}]", f"dustybox.eps={eps!r}", "dustybox.dim=3",
             "dustybox.n=20"])
        c = run(check + [out, "--ts", repr(ts), "--eps", repr(eps), "--max-error", "1e-3"], expect=None)
        print(c.stdout.strip())
        checks.check(c.returncode == 0, f"B2 (3D, 2 x 20^3), eps = {eps:g}, t_s = {ts:g}: v_D against eq. 31")
# Two species (dust.species = 2, each rho_D / rho_G = eps, own lattice and t_s), 1D, against the exact
# solution of the linear three-velocity system. Each pair's update takes the gas as driven by the non-drag
# forces alone, so a grain lags the drag acceleration the other species gives the gas by about dt / 2 of it:
# where both species are stiff (dt/t_s >= 11) v_D is within 2.5e-4 (asserted 1e-3); with t_s = 0.1 beside
# 1e-3 v_D is within 0.94 % (eps 0.01) and 0.41 % (eps 0.5) (asserted 2e-2). The drift
# v_D - v_G is printed, not asserted (wrong by factors where dt >> t_s; docs/sph_dust.md).
for eps in (0.01, 0.5):
    for ts, tol in (((1e-3, 1e-5), "1e-3"), ((0.1, 1e-3), "2e-2")):
        out = os.path.join(work, f"two_species_eps{eps:g}_ts{ts[0]:g}_{ts[1]:g}")
        run([exe, deck, f"output.dir={out}", "dust.species=2", f"dust.stopping_time=[{ts[0]!r}, {ts[1]!r}]",
             f"dustybox.eps={eps!r}"])
        c = run(check + [out, "--species-ts", repr(ts[0]), repr(ts[1]), "--eps", repr(eps), "--max-error", tol],
                expect=None)
        print(c.stdout.strip())
        checks.check(c.returncode == 0, f"two species, eps = {eps:g} each, t_s = {ts[0]:g}, {ts[1]:g}: v_D per species")
old = os.path.join(work, "original_ts0.001")
run([exe, deck, f"output.dir={old}", 'dust.drag_scheme="original"'])
png = os.path.join(work, "dustybox.png")
c = run(check + [os.path.join(work, "eps0.01_ts0.001"), old, "--ts", "1e-3", "--labels", "improved (eq. 17-19)",
                 "original (eq. 4-6)", "--plot", png], expect=None)
print(c.stdout.strip())
checks.check(c.returncode == 0 and os.path.getsize(png) > 10000, "the figure of both schemes")
sys.exit(checks.finish())
