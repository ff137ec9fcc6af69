"""VALIDATION E1/E2: coag_kernels against the analytic solutions of the
constant, additive and product kernels (relative L1 of the bin masses, mass
conserved to 1e-12) at 7 bins per mass decade with both product splits, the
RBO24 two-bin split (eq. 63) also on the finer grids where it meets the 2 %
ceiling, and the convergence of the constant-kernel error with bins per decade
for both splits.

At 7 bins per mass decade every case is asserted against its own measured
error times MARGIN (the recorded figures below, Serial build, rel_tol 1e-3 of
the deck), so that a change of either split shows; the default split (the deck
as written, no product_split override) must also meet the VALIDATION ceiling
of 2 %. The two-bin split exceeds that ceiling at 7 bins per decade for the
constant and additive kernels (an INFO line says by how much), which is why it
is not the default.

    coag_analytic.py COAG_KERNELS_EXE WORK_DIR"""
import os
import re
import shutil
import sys
import tomllib

from harness import Checks, fit_order, run, ROOT

exe, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)  # a fresh directory per run: output.dir belongs to one run
deck = os.path.join(ROOT, "problems", "coag_kernels", "coag_kernels.toml")
check_py = os.path.join(ROOT, "problems", "coag_kernels", "check.py")
c = Checks()
CEILING = 0.02  # VALIDATION E1/E2
MARGIN = 1.2
# Relative L1 errors measured at 7 bins per mass decade (kernel, T): quadratic, two-bin.
MEASURED_7 = {
    ("constant", 1000.0): {"quadratic": 7.555e-3, "two-bin": 3.013e-2},
    ("additive", 2.0): {"quadratic": 1.178e-2, "two-bin": 6.713e-2},
    ("product", 0.9): {"quadratic": 6.890e-3, "two-bin": 1.572e-2},
}


def case(name, kernel, t_end, bpd, split=None, max_error=CEILING):
    """Runs the deck (product_split from the deck unless `split`), checks with check.py; returns (L1, split)."""
    out = os.path.join(work, name)
    args = [exe, deck, f"coagulation.kernel=\"{kernel}\"", f"run.t_end={t_end}", f"output.snapshot_dt={t_end / 2}",
            f"analytic.bins_per_decade={bpd}", f"output.dir=\"{out}\"", "analytic.cells=2"]
    if split is not None:
        args.append(f"coagulation.product_split=\"{split}\"")
    run(args)
    p = run([sys.executable, check_py, out, "--max-error", str(max_error), "--mass-tol", "1e-12"], expect=None)
    print(p.stdout.strip())
    l1 = float(re.search(r"L1_rel = (\S+),", p.stdout).group(1))
    used = re.search(r"split = (\S+),", p.stdout).group(1)
    c.check(p.returncode == 0,
            f"{name}: {kernel} kernel, {used} split, T = {t_end}, {bpd} bins/decade: L1_rel {l1:.3e} <= {max_error:.4g}, "
            "mass to 1e-12")
    return l1, used


with open(deck, "rb") as f:
    deck_split = tomllib.load(f)["coagulation"].get("product_split")
c.check(deck_split is None, "the coag_kernels deck leaves coagulation.product_split at its default")

# E1 and E2 at 7 bins per mass decade with the default split: the VALIDATION ceiling and the recorded error.
for (kernel, T), measured in MEASURED_7.items():
    l1, used = case(f"{kernel}_7_default", kernel, T, 7)
    c.check(used == "quadratic", f"default product split is \"quadratic\" (got \"{used}\")")
    limit = MARGIN * measured[used]
    c.check(l1 <= min(limit, CEILING),
            f"default split, {kernel} kernel, 7 bins/decade: L1_rel {l1:.3e} <= {limit:.3e} ({MARGIN} x measured "
            f"{measured[used]:.3e}) and <= {CEILING}")

# The RBO24 two-bin option at 7 bins per decade, against its own recorded error.
for (kernel, T), measured in MEASURED_7.items():
    limit = MARGIN * measured["two-bin"]
    l1, _ = case(f"{kernel}_7_two_bin", kernel, T, 7, "two-bin", max_error=limit)
    print(f"INFO two-bin split, {kernel} kernel, 7 bins/decade: L1_rel {l1:.3e} is {l1 / CEILING:.2f} x the "
          f"VALIDATION ceiling {CEILING}")
# ... and on the grids where it meets the ceiling (E2).
case("additive_two_bin_20", "additive", 2.0, 20, "two-bin")
case("product_two_bin_10", "product", 0.9, 10, "two-bin")

bins = [7, 10, 20]
for split, min_order in (("quadratic", 2.0), ("two-bin", 1.5)):
    errs = [case(f"convergence_{split}_{b}", "constant", 100.0, b, split, max_error=1.0)[0] for b in bins]
    order = fit_order(bins, errs)
    print(f"constant kernel, {split} split, T = 100: L1_rel " + ", ".join(f"{e:.3e} ({b}/decade)" for b, e in zip(bins, errs)) +
          f"; order {order:.2f}")
    c.check(order >= min_order, f"constant kernel, {split} split: L1 error converges with bins per decade, order {order:.2f} >= {min_order}")
sys.exit(c.finish())
