#!/usr/bin/env python3
"""viscous_ring: VALIDATION C5 (and C6 for the gas).

usage: viscous_ring_convergence.py EXE WORKDIR N1 N2 N3 ...
1. Lynden-Bell & Pringle self-similar disc (nu ~ R) with analytic ("user")
   boundaries: mass-weighted L1 error at fitted order >= 1.8 (second order in
   space; dt ~ dR^2), finest error <= 1e-4.
2. Closed boundaries (nr = N1): total mass conserved to 1e-12, Sigma > 0.
3. Zero-torque boundaries at the explicit limit (gas.cfl = 1): Sigma > 0.
Both run with gas.Sigma_floor = 0, so a cell the update drove to or below zero
is clamped to 0 and fails the Sigma > 0 check (the default floor, 1e-100,
would hide it).
"""
import os
import shutil
import sys

from harness import Checks, fit_order, run

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "problems", "viscous_ring"))
import check as ring  # noqa: E402
import mote  # noqa: E402

exe, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)  # a fresh directory per run: output.dir belongs to one run
sizes = [int(n) for n in sys.argv[3:]]
deck = os.path.join(os.path.dirname(__file__), "..", "..", "problems", "viscous_ring", "viscous_ring.toml")
checks = Checks()

errors = []
for n in sizes:
    d = os.path.join(work, f"lbp_{n}")
    run([exe, deck, f"grid.nr={n}", f"output.dir={d}", "output.snapshot_dt=0"])
    errors.append(ring.l1_error(mote.last_snapshot(d)))
    print(f"nr = {n:4d}  L1 = {errors[-1]:.4e}")
order = fit_order(sizes, errors)
print(f"fitted order {order:.3f}")
checks.check(order >= 1.8, f"LBP self-similar: order {order:.3f} >= 1.8")
checks.check(errors[-1] <= 1e-4, f"LBP self-similar: finest L1 {errors[-1]:.3e} <= 1e-4")

for bc, extra in (("closed", []), ("zero_torque", ["gas.cfl=1.0"])):
    d = os.path.join(work, bc)
    run([exe, deck, f"grid.nr={sizes[0]}", f"gas.inner_boundary={bc}", f"gas.outer_boundary={bc}", f"output.dir={d}",
         "output.history_every=1", "gas.Sigma_floor=0", *extra])
    h = mote.read_history(os.path.join(d, "history.txt"))
    dm = abs(h["gas_mass"][-1] / h["gas_mass"][0] - 1)
    print(f"{bc}: |dM/M| = {dm:.3e} over {h['step'][-1]} steps, min Sigma = {h['Sigma_min'].min():.3e}")
    if bc == "closed":
        checks.check(dm <= 1e-12, f"closed: mass conserved, |dM/M| = {dm:.2e} <= 1e-12")
    checks.check(h["Sigma_min"].min() > 0, f"{bc}: Sigma stays positive")
sys.exit(checks.finish())
