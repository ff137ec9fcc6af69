#!/usr/bin/env python3
"""Check linear_solver runs (VALIDATION D1) against a direct dense solve.

    check.py RUN_DIR [RUN_DIR ...] [--expect-ladder] [--plot FILE.png]

For each run, from the system its last snapshot holds (CRS matrix A, right-hand
side b, the returned x and the report of every rung of the solve), with x_d
the solution of numpy's dense LU solve of the same A and b:
  * the solve converged;
  * relative residual: max_i |b - A x|_i / max(|b_i|, |A_ii x_i|) (RBO24 sec.
    4.1's fractional residual, computed here) <= the deck's
    linear_solver.tolerance;
  * solution error: max_i |x_i - x_d,i| / max(|x_d,i|, 1e-12 max|x_d|) <= 10 x
    that tolerance (per row: the FLD unknowns c E^b and B span many decades);
  * with --expect-ladder: the first rung failed and a later one converged;
  * INFO: iterations of every rung, ||b - A x||_2 / ||b||_2.
--plot draws the fractional residual after each iteration of every rung.
Prints PASS/FAIL/INFO lines and 'N passed, M failed'; exits non-zero on a failure.
"""
import argparse
import os
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import mote  # noqa: E402
from mote.verdict import Verdict  # noqa: E402

ERROR_FACTOR = 10.0  # VALIDATION D1: solution error <= 10 x tolerance
ROW_FLOOR = 1e-12    # rows of x_d below this fraction of max|x_d| are measured against it


def load(run_dir):
    snap = mote.last_snapshot(run_dir)
    d = snap.data
    n = len(d["rhs"])
    row_map, cols = d["row_map"].astype(int), d["columns"].astype(int)
    A = np.zeros((n, n))
    for r in range(n):
        A[r, cols[row_map[r]:row_map[r + 1]]] = d["values"][row_map[r]:row_map[r + 1]]
    attempts = [{"fill": int(d["attempt_fill_level"][k]), "iterations": int(d["attempt_iterations"][k]),
                 "converged": bool(d["attempt_converged"][k]), "history": d[f"history_{k}"]}
                for k in range(len(d["attempt_iterations"]))]
    deck = tomllib.loads(snap.deck)
    return {"A": A, "b": d["rhs"], "x": d["solution"], "attempts": attempts,
            "tolerance": deck.get("linear_solver", {}).get("tolerance", 1e-8), "kind": deck["system"]["kind"]}


def rung(fill):
    return "none" if fill < 0 else f"ILU({fill})"


def check_run(v, run_dir, expect_ladder):
    s = load(run_dir)
    A, b, x, tol = s["A"], s["b"], s["x"], s["tolerance"]
    name = f"{s['kind']} ({len(b)} rows)"
    r = b - A @ x
    fractional = np.max(np.abs(r) / np.maximum(np.abs(b), np.abs(np.diag(A) * x)))
    x_d = np.linalg.solve(A, b)
    error = np.max(np.abs(x - x_d) / np.maximum(np.abs(x_d), ROW_FLOOR * np.max(np.abs(x_d))))
    attempts = s["attempts"]
    v.info(f"{name}: " + "; ".join(f"{rung(a['fill'])} {'converged' if a['converged'] else 'failed'} after "
                                     f"{a['iterations']} iterations" for a in attempts)
           + f"; ||b - A x|| / ||b|| = {np.linalg.norm(r) / np.linalg.norm(b):.3e}")
    v.check(attempts and attempts[-1]["converged"], f"{name}: the solve converged")
    v.check(fractional <= tol, f"{name}: relative residual max_i |b - A x|_i / max(|b_i|, |A_ii x_i|) = "
                               f"{fractional:.3e} (<= tolerance {tol:g})")
    v.check(error <= ERROR_FACTOR * tol, f"{name}: error against the direct solve, max_i |x - x_d|_i / |x_d|_i = "
                                         f"{error:.3e} (<= {ERROR_FACTOR:g} x tolerance)")
    if expect_ladder:
        v.check(len(attempts) >= 2 and not attempts[0]["converged"],
                f"{name}: the first rung ({rung(attempts[0]['fill'])}) failed and the ladder went on to "
                f"{rung(attempts[-1]['fill'])}")
    return name, attempts


def plot(path, runs):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for name, attempts in runs:
        start = 0
        for a in attempts:
            h = a["history"]
            ax.semilogy(np.arange(start, start + len(h)), np.maximum(h, 1e-16), lw=1.2,
                        label=f"{name}, {rung(a['fill'])}")
            start += len(h)
    ax.set_ylim(bottom=1e-16)
    ax.set_xlabel("BiCGStab iteration (rungs of the ladder one after the other)")
    ax.set_ylabel("max fractional residual")
    ax.set_title("D1: ILU(k) + BiCGStab")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    print(f"wrote {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+")
    parser.add_argument("--expect-ladder", action="store_true")
    parser.add_argument("--plot")
    args = parser.parse_args()
    v = Verdict()
    results = [check_run(v, run, args.expect_ladder) for run in args.runs]
    if args.plot:
        plot(args.plot, results)
    return v.finish()


if __name__ == "__main__":
    sys.exit(main())
