#!/usr/bin/env python3
"""disc_hydrostatic: VALIDATION C4 and the gas velocities (RBO24 eq. 27-37).

usage: disc_hydrostatic_check.py EXE WORKDIR
1. The default deck (128 x 160 cells, one orbit): every threshold of
   problems/disc_hydrostatic/check.py (C4: rho to 1e-6 where rho > 1e-10 rho_mid,
   Sigma to 1e-12; v_phi, v_R against the exact disc and Takeuchi & Lin 2002;
   mass-weighted v_R against -3 nu / (2R) within 3 %; Sigma steady).
2. Three resolutions (64 x 80, 128 x 160, 256 x 320): v_phi and v_R converge to
   the exact vertically isothermal disc at fitted order >= 1.8.
"""
import os
import shutil
import sys

from harness import Checks, fit_order, run

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "problems", "disc_hydrostatic"))
import check as hydro  # noqa: E402

exe, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)  # a fresh directory per run: output.dir belongs to one run
deck = os.path.join(os.path.dirname(__file__), "..", "..", "problems", "disc_hydrostatic", "disc_hydrostatic.toml")
checks = Checks()

out_dir = os.path.join(work, "default")
run([exe, deck, f"output.dir={out_dir}"])
out, _ = hydro.analyse(out_dir)
# On the shipped deck some figures lie orders below check.py's VALIDATION ceilings
# (measured rho 2.0e-13, the steady Sigma 6.7e-16, v_phi against the pressure
# gradient 1.6e-3 and against TL02 7.4e-5): held here near them.
SHIPPED_DECK = {"rho_rel_err": 1e-10, "sigma_steady": 1e-12, "vphi_pressure_err": 5e-3, "vphi_tl02_rel_err": 3e-4}
for key, limit in hydro.THRESHOLDS.items():
    limit = min(limit, SHIPPED_DECK.get(key, limit))
    checks.check(out[key] <= limit, f"{key} = {out[key]:.3e} <= {limit:.1e}")
checks.check(1.6 < out["vR_mid_over_nu_R"] < 1.9,
             f"mid-plane v_R / (nu / R) = {out['vR_mid_over_nu_R']:.4f} (Takeuchi & Lin: +1.75, outflow)")

sizes, vphi_err, vR_err = [64, 128, 256], [], []
for n in sizes:
    d = os.path.join(work, f"n{n}")
    run([exe, deck, f"grid.nr={n}", f"grid.ntheta={n * 5 // 4}", "run.t_end=0", f"output.dir={d}"])
    o, _ = hydro.analyse(d)
    vphi_err.append(o["vphi_pressure_err"])
    vR_err.append(o["vR_exact_err"])
    print(f"nr = {n:4d}: v_phi^2 error / cs^2 = {vphi_err[-1]:.4e}, v_R error / (nu/R) = {vR_err[-1]:.4e}, rho {o['rho_rel_err']:.2e}, Sigma {o['sigma_rel_err']:.2e}")
    checks.check(o["rho_rel_err"] <= 1e-6 and o["sigma_rel_err"] <= 1e-12, f"nr = {n}: C4 rho and Sigma")
for name, errs in (("v_phi", vphi_err), ("v_R", vR_err)):
    order = fit_order(sizes, errs)
    print(f"{name}: fitted order {order:.3f}")
    checks.check(order >= 1.8, f"{name}: order {order:.3f} >= 1.8")
checks.check(vR_err[-1] <= 0.03, f"v_R finest error {vR_err[-1]:.3e} <= 0.03 nu / R")
sys.exit(checks.finish())
