#!/usr/bin/env python3
"""sph_dustydiffuse convergence (PL15 sec. 4.3 and Fig. 6, VALIDATION A3).

CI: cubic lattices n^3 = 8^3, 16^3, 32^3 to t = 0.1 with both discretisations
(deck sph_dustydiffuse.toml): the fitted order of the direct second
derivatives is >= 1.8, they are at least 2x more accurate than two first
derivatives at every n, L2_abs(eps, r < 0.2) <= 5e-4 at 32^3, and the dust
mass is conserved to 1e-12. `full` adds 64^3 to the convergence study and the
paper's run (sph_dustydiffuse_full.toml, close-packed 50 x 58 x 62 to t = 1):
L2_abs <= 5e-4 at t = 0.1, 0.3 and 1.

usage: sph_dustydiffuse.py EXE WORKDIR [full]
"""
import importlib.util
import os
import shutil
import sys

from harness import ROOT, Checks, fit_order, run

exe, work = sys.argv[1], sys.argv[2]
full = len(sys.argv) > 3 and sys.argv[3] == "full"
shutil.rmtree(work, ignore_errors=True)
pdir = os.path.join(ROOT, "problems", "sph_dustydiffuse")
spec = importlib.util.spec_from_file_location("dustydiffuse_check", os.path.join(pdir, "check.py"))
check = importlib.util.module_from_spec(spec)
spec.loader.exec_module(check)

checks = Checks()
ns = (8, 16, 32, 64) if full else (8, 16, 32)
l2 = {}
for disc in ("second_derivatives", "first_derivatives"):
    for n in ns:
        out = os.path.join(work, f"{disc}_{n}")
        run([exe, os.path.join(pdir, "sph_dustydiffuse.toml"), f"output.dir={out}", f"dustydiffuse.n={n}",
             f'dust.discretisation="{disc}"'])
        (res,), drift = check.errors(out)
        l2[disc, n] = res[1]
        print(f"{disc} {n}^3: L2_abs(eps, r < 0.2) at t = {res[0]:g}: {res[1]:.3e}; dust mass drift {drift:.1e}")
        checks.check(drift <= 1e-12, f"dust mass conserved to 1e-12 ({disc}, {n}^3)")
    order = fit_order(ns, [l2[disc, n] for n in ns])
    print(f"{disc}: fitted order {order:.2f}")
    if disc == "second_derivatives":
        checks.check(order >= 1.8, f"direct second derivatives: order {order:.2f} >= 1.8")
        checks.check(l2[disc, 32] <= 5e-4, f"direct second derivatives at 32^3: {l2[disc, 32]:.2e} <= 5e-4")
for n in ns:
    ratio = l2["first_derivatives", n] / l2["second_derivatives", n]
    checks.check(ratio >= 2.0, f"{n}^3: two first / direct second derivatives = {ratio:.2f} >= 2")
if full:
    out = os.path.join(work, "full")
    run([exe, os.path.join(pdir, "sph_dustydiffuse_full.toml"), f"output.dir={out}"])
    c = run([sys.executable, os.path.join(pdir, "check.py"), out, "--times", "0.1", "0.3", "1", "--plot",
             out + ".png"], expect=None)
    print(c.stdout.strip())
    checks.check(c.returncode == 0, "close-packed 50 x 58 x 62: L2_abs(eps, r < 0.2) <= 5e-4 at t = 0.1, 0.3, 1")
sys.exit(checks.finish())
