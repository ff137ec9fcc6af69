"""The verdict of a check script: PASS/FAIL lines for thresholded checks, INFO
lines for figures without a threshold (they count neither way), and a closing
'N passed, M failed' line with the exit status (0 only if something passed and
nothing failed). Every problems/*/check.py ends with it."""


class Verdict:
    """check(ok, text) prints PASS or FAIL and counts it, info(text) prints INFO; finish() prints the
    closing line and returns the exit status."""

    def __init__(self):
        self.passed = self.failed = 0

    def check(self, ok, text):
        ok = bool(ok)
        print(("PASS " if ok else "FAIL ") + text, flush=True)
        self.passed += ok
        self.failed += not ok

    def info(self, text):
        print("INFO " + text, flush=True)

    def finish(self):
        print(f"{self.passed} passed, {self.failed} failed")
        return 0 if self.failed == 0 and self.passed > 0 else 1


def sph_conservation(v, run_dir, energy_tol, momentum_tol=1e-12, mass=True):
    """VALIDATION A7 from an SPH run's history.txt: total mass to 1e-12 relative (if `mass`), the dust mass before
    the floor (a one-fluid run's dust_mass_unfloored column) to 1e-12 relative, x momentum to momentum_tol of the
    run's momentum scale (the largest sum m|v| of the history), total energy to energy_tol relative; each a PASS or
    FAIL line of the Verdict v."""
    import os

    import numpy as np

    from .history import read_history

    path = os.path.join(run_dir, "history.txt")
    if not os.path.exists(path):
        v.check(False, f"conservation: no {path}")
        return
    h = read_history(path)
    m0 = h["mass"][0]
    p_scale = max(h["momentum_abs"]) if "momentum_abs" in h.dtype.names else m0
    dm, dp = abs(h["mass"][-1] - m0) / m0, abs(h["momentum_x"][-1] - h["momentum_x"][0]) / p_scale
    de = abs(h["energy"][-1] - h["energy"][0]) / abs(h["energy"][0])
    if mass:
        v.check(dm <= 1e-12, f"mass conserved: relative drift {dm:.1e} <= 1e-12")
    if "dust_mass_unfloored" in h.dtype.names:
        dust = h["dust_mass_unfloored"]
        dd = np.max(np.abs(dust - dust[0])) / dust[0]
        v.check(dd <= 1e-12, f"dust mass (before the floor) conserved: largest relative drift {dd:.1e} <= 1e-12")
    v.check(dp <= momentum_tol, f"momentum conserved: drift {dp:.1e} <= {momentum_tol:g} of the largest sum m|v|")
    v.check(de <= energy_tol, f"total energy conserved: relative drift {de:.1e} <= {energy_tol:g}")
