#!/usr/bin/env python3
"""The figure of the Pinte et al. (2009) benchmark in the style of RBO24 Fig. 9.

    plot_pinte.py LOW_RUN HIGH_RUN [--fine LOW_FINE HIGH_FINE] [--out FILE.png]

Mid-plane and top-of-grid (surface) temperatures against R - R_in for the
two disc masses (pinte_low.toml: 1e-2 M_earth, pinte_high.toml: 10 M_earth),
with the optically thin temperature of the top row's grain mixture (check.py)
and, given --fine, the runs at 1.5x the resolution ("-" for none). RBO24 compare with
RADMC-3D; no such table is public, so the reference curves here are the
optically thin limit and the resolution study.
"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import check  # noqa: E402


def curves(run_dir):
    out = check.analyse(run_dir)
    check.pinte_checks(run_dir, out)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("low")
    parser.add_argument("high")
    parser.add_argument("--fine", nargs=2, metavar=("LOW_FINE", "HIGH_FINE"))
    parser.add_argument("--out", default="pinte.png")
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    titles = [r"$10^{-2}\,M_\oplus$", r"$10\,M_\oplus$"]
    fines = args.fine or [None, None]
    for ax, run, fine, title in zip(axes, [args.low, args.high], fines, titles):
        out = curves(run)
        x = out["R"] - out["R_in"]
        ax.loglog(x, out["T"][:, -1], "C0", label="surface (top row)")
        ax.loglog(x, out["T_thin"], "C0--", lw=1, label="optically thin limit")
        ax.loglog(x, out["T"][:, 0], "C3", label="mid-plane")
        if fine and fine != "-":
            f = check.analyse(fine)
            xf = f["R"] - f["R_in"]
            ax.loglog(xf, f["T"][:, -1], "k:", lw=1, label="1.5x resolution")
            ax.loglog(xf, f["T"][:, 0], "k:", lw=1)
        ax.set_title(title)
        ax.set_xlabel("R - R_in [au]")
    axes[0].set_ylabel("T [K]")
    axes[0].legend()
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
