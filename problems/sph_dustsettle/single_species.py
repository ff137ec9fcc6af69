#!/usr/bin/env python3
"""A6 against single-species runs (HPL18 sec. 4.3.2, Fig. 4; VALIDATION A6).

    single_species.py EXE MULTI_RUN_DIR WORK_DIR [--jobs 1] [--max-diff 0.05 | --diff-bounds B1 .. BN]
                      [--zmax 2] [--multi-log LOG] [--reuse]

Re-runs the deck of a finished N-species sph_dustsettle run (read from its
snapshots) once per species with only that species (same size, same eps_j,
same relaxed column) into WORK_DIR/single_<j>, then compares, particle by
particle (matched by id) at the last snapshot, the dust fraction eps_j of the
MULTIGRAIN run with that of its single-species run:
    diff_j = sqrt(mean((eps_j,multi - eps_single)^2)) / max(eps_single),
over all particles and over those with |z| < zmax H. The runs differ
physically only through the back-reaction of the other species on the gas
(total eps = 1/101 for Table 1, so eps_j shifts by ~1 %): HPL18 Fig. 4-5.
The PASS region is |z| < 2H by default: above it the largest grains reach
Stokes numbers of 0.1-0.8 (1 mm at 3H), where the terminal-velocity
approximation fails (PL15 sec. 2.2) and, through tilde T_sj (HPL18 eq. 15),
moves the small grains of the MULTIGRAIN run on the few free-surface
particles; both numbers are printed. Also
prints the wall time of the N-species run against the mean single run (HPL18
sec. 4.3.3: N = 10 costs 2x one N = 1 run; VALIDATION asks <= 2x, goal 1.5x).
PASS when every diff_j (|z| < zmax H) <= --max-diff (or species j's bound of
--diff-bounds) and the cost ratio <= 2.
"""
import argparse
import concurrent.futures
import os
import re
import subprocess
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import check  # noqa: E402
import mote  # noqa: E402


def last_state(run_dir):
    import h5py

    with h5py.File(mote.list_snapshots(run_dir)[-1]) as f:
        ids = f["particles/id"][...]
        eps = f["particles/dust_fraction"][...].reshape(len(ids), -1)
        deck = f.attrs["deck"]
        deck = deck.decode() if isinstance(deck, bytes) else deck
        z = f["particles/position"][:, check.vertical_axis(deck)]
    order = np.argsort(ids)
    return ids[order], eps[order], z[order], deck


def wall_seconds(log_text):
    m = re.search(r"finished: .* in ([0-9.]+) s", log_text)
    return float(m.group(1)) if m else float("nan")


def run_single(exe, deck_path, out, size, eps, reuse):
    if reuse and os.path.exists(out + ".log"):
        return wall_seconds(open(out + ".log").read())
    args = [exe, deck_path, f"output.dir={out}", "dust.species=1", 'dust.method="diffusion"',
            'dust.sizes_from="list"', f"dust.sizes=[{size!r}]", f"dust.eps=[{eps!r}]"]
    r = subprocess.run(args, capture_output=True, text=True)
    with open(out + ".log", "w") as f:
        f.write(r.stdout + r.stderr)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(args)} failed:\n{r.stderr[-2000:]}")
    return wall_seconds(r.stdout + r.stderr)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("exe")
    ap.add_argument("multi_run")
    ap.add_argument("work")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--max-diff", type=float, default=0.05)
    ap.add_argument("--diff-bounds", type=float, nargs="+", help="one bound per species instead of --max-diff")
    ap.add_argument("--reuse", action="store_true", help="keep single runs already in WORK_DIR")
    ap.add_argument("--zmax", type=float, default=2.0, help="PASS region |z| < zmax H")
    ap.add_argument("--multi-log", help="stdout of the N-species run (its 'finished ... in X s' line)")
    args = ap.parse_args()
    ids, eps_multi, z, deck_text = last_state(args.multi_run)
    deck = tomllib.loads(deck_text)
    du = deck["dust"]
    if du["sizes_from"] == "power_law":
        sizes, eps0 = check.power_law(du)
    else:
        sizes, eps0 = np.resize(du["sizes"], du["species"]), np.resize(du["eps"], du["species"])
    bounds = args.diff_bounds or [args.max_diff] * len(sizes)
    if len(bounds) != len(sizes):
        ap.error(f"--diff-bounds: {len(bounds)} bounds for {len(sizes)} species")
    os.makedirs(args.work, exist_ok=True)
    deck_path = os.path.join(args.work, "deck.toml")
    with open(deck_path, "w") as f:
        f.write(deck_text)
    outs = [os.path.join(args.work, f"single_{j + 1}") for j in range(len(sizes))]
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        walls = list(pool.map(lambda j: run_single(args.exe, deck_path, outs[j], float(sizes[j]), float(eps0[j]),
                                                     args.reuse),
                              range(len(sizes))))
    ok = True
    H = deck["settle"]["H_over_R"] * deck["settle"]["R0"]
    inside = np.abs(z) < args.zmax * H
    print(f"species  size [cm]  eps_j     diff (L2 / max): all {len(z)} particles, {inside.sum()} with |z| < {args.zmax:g} H")
    for j, out in enumerate(outs):
        ids1, eps1, _, _ = last_state(out)
        if not np.array_equal(ids, ids1):
            raise RuntimeError(f"{out}: particles differ from the MULTIGRAIN run")
        scale = np.abs(eps1[:, 0]).max()
        d_all = np.sqrt(np.mean((eps_multi[:, j] - eps1[:, 0]) ** 2)) / scale
        d = np.sqrt(np.mean((eps_multi[inside, j] - eps1[inside, 0]) ** 2)) / scale
        ok = ok and d <= bounds[j]
        print(f"{j + 1:7d}  {sizes[j]:.3e}  {eps0[j]:.2e}  {d_all:.3e}  {d:.3e}  (<= {bounds[j]:.3g}: "
              f"{'PASS' if d <= bounds[j] else 'FAIL'})")
    single_mean = float(np.mean(walls))
    print(f"wall time per single-species run (evolution, without relaxation): {single_mean:.1f} s "
          f"(mean of {len(walls)})")
    if args.multi_log:
        multi = wall_seconds(open(args.multi_log).read())
        ratio = multi / single_mean
        ok = ok and ratio <= 2.0
        print(f"{'PASS' if ratio <= 2.0 else 'FAIL'} N = {len(sizes)} run {multi:.1f} s = {ratio:.2f} x one single run")
    else:
        print("(no --multi-log: cost ratio not measured)")
    within = " ".join(f"{b:g}" for b in bounds) if args.diff_bounds else f"{args.max_diff:g}"
    print(("PASS" if ok else "FAIL") + f": MULTIGRAIN vs single-species runs within {within} for |z| < {args.zmax:g} H")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
