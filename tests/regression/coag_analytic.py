"""VALIDATION E1/E2: coag_kernels against the analytic solutions of the
constant, additive and product kernels (relative L1 of the bin masses <= 2 %,
mass conserved to 1e-12) at 7 bins per mass decade with the limited quadratic
product split (the coag_kernels deck), the RBO24 two-bin split (eq. 63) on the
finer grids it needs, and the convergence of the constant-kernel error with
bins per decade for both splits.

    coag_analytic.py COAG_KERNELS_EXE WORK_DIR"""
import os
import re
import shutil
import sys

from harness import Checks, fit_order, run, ROOT

exe, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)  # a fresh directory per run: output.dir belongs to one run
deck = os.path.join(ROOT, "problems", "coag_kernels", "coag_kernels.toml")
check_py = os.path.join(ROOT, "problems", "coag_kernels", "check.py")
c = Checks()


def case(name, kernel, t_end, bpd, split, max_error=0.02):
    out = os.path.join(work, name)
    run([exe, deck, f"coagulation.kernel=\"{kernel}\"", f"coagulation.product_split=\"{split}\"", f"run.t_end={t_end}",
         f"output.snapshot_dt={t_end / 2}", f"analytic.bins_per_decade={bpd}", f"output.dir=\"{out}\"", "analytic.cells=2"])
    p = run([sys.executable, check_py, out, "--max-error", str(max_error), "--mass-tol", "1e-12"], expect=None)
    print(p.stdout.strip())
    l1 = float(re.search(r"L1_rel = (\S+),", p.stdout).group(1))
    c.check(p.returncode == 0,
            f"{name}: {kernel} kernel, {split} split, T = {t_end}, {bpd} bins/decade: L1_rel {l1:.3e} <= {max_error}, mass to 1e-12")
    return l1


# E1 and E2 at 7 bins per mass decade (quadratic split).
case("constant_7", "constant", 1000.0, 7, "quadratic")
case("additive_7", "additive", 2.0, 7, "quadratic")
case("product_7", "product", 0.9, 7, "quadratic")
# The RBO24 two-bin split: E2 on the grids it needs, and its 7-per-decade figures as a ceiling.
case("additive_two_bin", "additive", 2.0, 20, "two-bin")
case("product_two_bin", "product", 0.9, 10, "two-bin")
case("product_two_bin_7", "product", 0.5, 7, "two-bin")
case("constant_two_bin_7", "constant", 1000.0, 7, "two-bin", max_error=0.035)
bins = [7, 10, 20]
for split, min_order in (("quadratic", 2.0), ("two-bin", 1.5)):
    errs = [case(f"convergence_{split}_{b}", "constant", 100.0, b, split, max_error=1.0) for b in bins]
    order = fit_order(bins, errs)
    print(f"constant kernel, {split} split, T = 100: L1_rel " + ", ".join(f"{e:.3e} ({b}/decade)" for b, e in zip(bins, errs)) +
          f"; order {order:.2f}")
    c.check(order >= min_order, f"constant kernel, {split} split: L1 error converges with bins per decade, order {order:.2f} >= {min_order}")
sys.exit(c.finish())
