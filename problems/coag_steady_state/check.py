#!/usr/bin/env python3
"""Check (and plot) a coag_steady_state run (RBO24 Fig. 10, VALIDATION E3).

    check.py RUN_DIR [--plot FILE.png] [--steady-tol 0.02] [--mass-tol 1e-10] [--cut-fraction 0.01]
             [--same-as OTHER_RUN --max-l1 L1] [--scaling OTHER_RUN --scaling-tol TOL]

Reads the snapshots, computes sigma_d(m) = m dSigma/dm (eq. 69) and checks
  * steady state: relative L1 change of sigma_d between the last two snapshots
    (divided by the time between them, times the last tenth of the run) <= steady-tol,
  * mass conservation: |Sigma_d(t) / Sigma_d(0) - 1| <= mass-tol at every snapshot,
  * cut-off at the fragmentation limit: the peak of a^... sigma_d lies within
    [0.8, 1.25] a_frag, a_frag = 2 Sigma_g v_frag^2 / (3 pi rho_m alpha c_s^2)
    (Birnstiel et al. 2012; measured 0.977-1.069 on grids of 23 to 200 species:
    a barrier off by sqrt(2) in v_frag moves the peak by a factor 2), and sigma_d has dropped below 1e-3 of its peak by 3 a_frag,
  * with --same-as: the steady state does not depend on the initial distribution:
    relative L1 difference sum|sigma_d - sigma_d,other| / sum sigma_d,other of the last
    snapshots of the two runs (same mass grid) <= max-l1,
  * with --scaling: the cut-off moves as a_frag ~ v_frag^2: a_cut / a_cut,other within
    scaling-tol (relative) of (v_frag / v_frag,other)^2, the v_frag values from the two decks.
The cut-off a_cut is the grain size above the peak of sigma_d at which sigma_d first
falls to cut-fraction (default 1e-2) of its peak value, interpolated linearly in
(log a, log sigma_d) between the two bins around the crossing; it is printed for every run.
Exits non-zero on failure; prints 'N passed, M failed'.
"""
import argparse
import math
import os
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import mote  # noqa: E402
from mote.verdict import Verdict  # noqa: E402

K_B, M_H, G, M_SUN, AU, YEAR = 1.380649e-16, 1.6735575e-24, 6.67430e-8, 1.98840987e33, 1.495978707e13, 3.15576e7


def fragmentation_limit(deck):
    c, d = deck["coagulation"], deck["disc"]
    cs2 = K_B * d["temperature"] / (c["mu"] * M_H)
    return 2 * d["sigma_gas"] * c["v_frag"] ** 2 / (3 * math.pi * c["rho_m"] * d["alpha"] * cs2)


def cut_off(a, sig, fraction):
    """Grain size above the peak of sig at which sig first falls to fraction x peak (log-log interpolation);
    nan if it does not fall that far on the grid."""
    k = int(np.argmax(sig))
    below = np.nonzero(sig[k:] <= fraction * sig[k])[0]
    if len(below) == 0:
        return math.nan
    j = k + int(below[0])
    la, ls, x = np.log(a[j - 1:j + 1]), np.log(np.maximum(sig[j - 1:j + 1], 1e-300)), math.log(fraction * sig[k])
    return math.exp(la[0] + (x - ls[0]) / (ls[1] - ls[0]) * (la[1] - la[0]))


def final_state(run_dir):
    """(deck, grain sizes, sigma_d) of the last snapshot of a run."""
    last = mote.read_snapshot(mote.list_snapshots(run_dir)[-1])
    return tomllib.loads(last.deck), last.data["grain_size"], last.data["sigma_d"][0]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir")
    ap.add_argument("--plot")
    ap.add_argument("--steady-tol", type=float, default=0.02)
    ap.add_argument("--mass-tol", type=float, default=1e-10)
    ap.add_argument("--cut-fraction", type=float, default=1e-2)
    ap.add_argument("--same-as", metavar="OTHER_RUN")
    ap.add_argument("--max-l1", type=float, default=3e-3)
    ap.add_argument("--scaling", metavar="OTHER_RUN")
    ap.add_argument("--scaling-tol", type=float, default=0.1)
    args = ap.parse_args()
    snaps = [mote.read_snapshot(p) for p in mote.list_snapshots(args.run_dir)]
    if len(snaps) < 3:
        print("need at least 3 snapshots")
        return 1
    deck = tomllib.loads(snaps[-1].deck)
    a = snaps[-1].data["grain_size"]
    sig = [s.data["sigma_d"][0] for s in snaps]
    tot = np.array([s.data["density"][0].sum() for s in snaps])
    a_frag = fragmentation_limit(deck)
    v = Verdict()
    check = v.check

    t = np.array([s.time for s in snaps])
    change = np.sum(np.abs(sig[-1] - sig[-2])) / np.sum(sig[-1])
    rate = change / (t[-1] - t[-2]) * 0.1 * t[-1]
    check(rate <= args.steady_tol,
          f"steady state: L1 change {change:.3e} between t = {t[-2] / YEAR:.4g} and {t[-1] / YEAR:.4g} yr "
          f"({rate:.3e} per tenth of the run <= {args.steady_tol})")
    merr = np.max(np.abs(tot / tot[0] - 1))
    check(merr <= args.mass_tol, f"mass conserved: max |Sigma_d / Sigma_d(0) - 1| = {merr:.3e} <= {args.mass_tol:g}")
    s = sig[-1]
    peak = int(np.argmax(s))
    check(0.8 * a_frag <= a[peak] <= 1.25 * a_frag,
          f"peak of sigma_d at a = {a[peak]:.3e} cm within [0.8, 1.25] a_frag, a_frag = {a_frag:.3e} cm")
    beyond = a >= 3 * a_frag
    drop = np.max(s[beyond]) / s[peak] if np.any(beyond) else 0.0
    check(drop < 1e-3, f"cut-off: max sigma_d beyond 3 a_frag / peak = {drop:.3e} < 1e-3")
    a_cut = cut_off(a, s, args.cut_fraction)
    print(f"coag_steady_state: t = {t[-1] / YEAR:.4g} yr, species = {len(a)}, v_frag = {deck['coagulation']['v_frag']:g} cm/s, "
          f"a_init_max = {deck['disc']['a_init_max']:g} cm, a_frag = {a_frag:.4e} cm, a_peak = {a[peak]:.4e} cm, "
          f"a_cut({args.cut_fraction:g} of peak) = {a_cut:.4e} cm = {a_cut / a_frag:.3f} a_frag, Sigma_d = {tot[-1]:.6e} g/cm^2")
    if args.same_as:
        odeck, oa, osig = final_state(args.same_as)
        if len(oa) != len(a) or not np.allclose(oa, a, rtol=1e-12):
            check(False, f"initial-state independence: {args.same_as} has another mass grid")
        else:
            l1 = np.sum(np.abs(s - osig)) / np.sum(osig)
            check(l1 <= args.max_l1,
                  f"initial-state independence: L1(sigma_d) = {l1:.3e} <= {args.max_l1:g} against {args.same_as} "
                  f"(a_init_max {deck['disc']['a_init_max']:g} vs {odeck['disc']['a_init_max']:g} cm)")
    if args.scaling:
        odeck, oa, osig = final_state(args.scaling)
        o_cut = cut_off(oa, osig, args.cut_fraction)
        expected = (deck["coagulation"]["v_frag"] / odeck["coagulation"]["v_frag"]) ** 2
        ratio = a_cut / o_cut
        check(abs(ratio / expected - 1) <= args.scaling_tol,
              f"cut-off scaling: a_cut ratio {a_cut:.4e} / {o_cut:.4e} = {ratio:.4f}, (v_frag ratio)^2 = {expected:.4f}, "
              f"relative difference {ratio / expected - 1:+.3e} within {args.scaling_tol:g}; "
              f"a_peak ratio {a[peak] / oa[int(np.argmax(osig))]:.4f}")
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for s_, snap in list(zip(sig, snaps))[:: max(1, len(snaps) // 6)] + [(sig[-1], snaps[-1])]:
            ax.loglog(a, np.maximum(s_, 1e-30), label=f"{snap.time / YEAR:.3g} yr")
        ax.axvline(a_frag, ls="--", c="k", lw=0.8, label="fragmentation limit")
        ax.set(xlabel="grain size a [cm]", ylabel=r"$\sigma_d = m\,\partial\Sigma_d/\partial m$ [g cm$^{-2}$]",
               ylim=(max(1e-8, s.max() * 1e-6), s.max() * 3), title="coag_steady_state (RBO24 Fig. 10)")
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)
        print(f"wrote {args.plot}")
    return v.finish()


if __name__ == "__main__":
    sys.exit(main())
