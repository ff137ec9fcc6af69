"""VALIDATION E1/E2: coag_kernels against the analytic solutions of the
constant, additive and product kernels (relative L1 of the bin masses <= 2 %,
mass conserved to 1e-12) and the convergence of the constant-kernel error with
bins per decade.

    coag_analytic.py COAG_KERNELS_EXE WORK_DIR"""
import os
import re
import sys

from harness import Checks, fit_order, run, ROOT

exe, work = sys.argv[1], sys.argv[2]
deck = os.path.join(ROOT, "problems", "coag_kernels", "coag_kernels.toml")
check_py = os.path.join(ROOT, "problems", "coag_kernels", "check.py")
c = Checks()


def case(name, kernel, t_end, bpd, max_error=0.02):
    out = os.path.join(work, name)
    run([exe, deck, f"coagulation.kernel=\"{kernel}\"", f"run.t_end={t_end}", f"output.snapshot_dt={t_end / 2}",
         f"analytic.bins_per_decade={bpd}", f"output.dir=\"{out}\"", "analytic.cells=2"])
    p = run([sys.executable, check_py, out, "--max-error", str(max_error), "--mass-tol", "1e-12"], expect=None)
    print(p.stdout.strip())
    l1 = float(re.search(r"L1_rel = (\S+),", p.stdout).group(1))
    c.check(p.returncode == 0, f"{name}: {kernel} kernel, T = {t_end}, {bpd} bins/decade: L1_rel {l1:.3e} <= {max_error}, mass to 1e-12")
    return l1


case("constant", "constant", 1000.0, 10)
case("additive", "additive", 2.0, 20)
case("product", "product", 0.9, 10)
case("product_7", "product", 0.5, 7)
errs = [case(f"constant_{b}", "constant", 100.0, b, max_error=1.0) for b in (7, 10, 20)]
order = fit_order([7, 10, 20], errs)
c.check(order >= 1.5, f"constant kernel: L1 error converges with bins per decade, order {order:.2f} >= 1.5")
sys.exit(c.finish())
