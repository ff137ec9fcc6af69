#!/usr/bin/env python3
"""RBO24 sec. 3.6 / VALIDATION C1: a Gaussian pulse advected and diffused on
the non-orthogonal (R, theta) grid converges at second order.

usage: disc_pulse_convergence.py EXE WORKDIR N1 N2 N3 ...
The L2 norm sqrt(sum (rho - rho_an)^2 / N^2) of RBO24 is recomputed here from
the snapshots and eq. 38; the fitted order must be >= 1.8 (VALIDATION: order 2
means slope >= p - 0.2), and the error must fall at every refinement.
"""
import os
import shutil
import sys
import tomllib

import numpy as np

from harness import Checks, fit_order, run
import mote

exe, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)  # a fresh directory per run: output.dir belongs to one run
sizes = [int(n) for n in sys.argv[3:]]
deck = os.path.join(os.path.dirname(__file__), "..", "..", "problems", "disc_pulse", "disc_pulse.toml")


def analytic(snap):
    p = tomllib.loads(snap.deck)["pulse"]
    R = snap.data["R_centres"][:, None]
    Z = R * np.tan(snap.data["theta_centres"][None, :])
    t = p["t0"] + snap.time
    xp, yp = p["x0"] + p["vx"] * snap.time, p["y0"] + p["vy"] * snap.time
    return p["amplitude"] / t * np.exp(-((R - xp) ** 2 + (Z - yp) ** 2) / (4 * p["diffusivity"] * t))


checks = Checks()
errors = []
for n in sizes:
    out = os.path.join(work, f"n{n}")
    run([exe, deck, f"grid.nr={n}", f"grid.ntheta={n}", f"output.dir={out}", "output.snapshot_dt=0"])
    snap = mote.last_snapshot(out)
    rho = snap.fields["dust_density"]
    err = float(np.sqrt(np.sum((rho - analytic(snap)) ** 2) / rho.size))
    errors.append(err)
    print(f"N = {n:4d}  L2 = {err:.4e}")
order = fit_order(sizes, errors)
print(f"fitted order {order:.3f}")
checks.check(order >= 1.8, f"second order: fitted slope {order:.3f} >= 1.8")
checks.check(all(b < a for a, b in zip(errors, errors[1:])), "error decreases at every refinement")
hist = mote.read_history(os.path.join(work, f"n{sizes[-1]}", "history.txt"))
checks.check(np.all(np.isfinite(hist["dust_mass"])) and np.all(hist["dust_mass"] > 0), "dust mass finite and positive")
sys.exit(checks.finish())
