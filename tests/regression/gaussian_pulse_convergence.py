#!/usr/bin/env python3
"""gaussian_pulse: second-order convergence against the analytic solution.

usage: gaussian_pulse_convergence.py EXE WORKDIR N1 N2 N3 ...
Unlimited (Fromm) and MC-limited reconstructions must converge at order >= 1.8
(VALIDATION: "order p" = fitted slope >= p - 0.2; the pulse is smooth, so the
limiter must not degrade the order); the finest error must stay below 1e-3.
"""
import os
import shutil
import sys

from harness import Checks, fit_order, run

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "problems", "gaussian_pulse"))
import check as pulse  # noqa: E402
import mote  # noqa: E402

exe, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)  # a fresh directory per run: output.dir belongs to one run
sizes = [int(n) for n in sys.argv[3:]]
deck = os.path.join(os.path.dirname(__file__), "..", "..", "problems", "gaussian_pulse", "gaussian_pulse.toml")
checks = Checks()
for limiter, min_order in (("none", 1.8), ("mc", 1.8)):
    errors = []
    for n in sizes:
        out = os.path.join(work, f"pulse_{limiter}_{n}")
        run([exe, deck, f"grid.nx={n}", f"grid.ny={n}", f"scheme.limiter={limiter}", f"output.dir={out}",
             "output.snapshot_dt=0"])
        errors.append(pulse.l2_rel(mote.last_snapshot(out)))
        print(f"limiter {limiter:5s} N = {n:4d}  L2_rel = {errors[-1]:.4e}")
    order = fit_order(sizes, errors)
    print(f"limiter {limiter}: fitted order {order:.3f}")
    checks.check(order >= min_order, f"limiter {limiter}: order {order:.3f} >= {min_order}")
    checks.check(errors[-1] <= 1e-3, f"limiter {limiter}: finest L2_rel {errors[-1]:.3e} <= 1e-3")
sys.exit(checks.finish())
