"""python/mote/opacity_tables.py: a dsharp_opac npz (the DSHARP opacities of
Birnstiel et al. 2018 as that package stores them) converted to the DSHARP
table format. The npz here is synthetic, in the package's layout (a, lam in
cm; k_abs, k_sca, g over (a, lam)), from the geometric absorption law
k_abs = 3 / (4 rho a) min(1, 2 pi a / lambda), with one slightly negative g as
in the real file. Checks: the
rows hold the npz's values (wavelengths in um, sizes slowest), the negative g
kept; the transition disc's non-isothermal CI deck reads the table at set-up
and runs two steps; a npz without the arrays and a bad command line are
refused with an error.
Usage: dsharp_opac_table.py <python dir> <transition_disc> <decks dir> <work dir>"""

import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, sys.argv[1])
from mote.verdict import Verdict  # noqa: E402

exe, decks, work = sys.argv[2], sys.argv[3], sys.argv[4]
os.makedirs(work, exist_ok=True)
v = Verdict()


def check(name, ok, detail):
    v.check(ok, name + ": " + detail)


sizes = np.array([1e-5, 1e-3, 1e-1, 1.0])
lams = np.geomspace(1e-5, 1.0, 9)  # cm
k_abs = 3.0 / (4.0 * 1.675 * sizes[:, None]) * np.minimum(1.0, 2.0 * np.pi * sizes[:, None] / lams[None, :])
k_sca = 0.5 * k_abs
g = np.outer(np.linspace(0.2, 0.9, len(sizes)), np.ones(len(lams)))
g[0, -1] = -1.5e-6
npz = os.path.join(work, "synthetic_dsharp.npz")
np.savez(npz, a=sizes, lam=lams, k_abs=k_abs, k_sca=k_sca, g=g, rho_s=np.float64(1.675))
table = os.path.join(work, "dsharp.dat")
run = subprocess.run([sys.executable, "-m", "mote.opacity_tables", "dsharp_opac", npz, table],
                     env=dict(os.environ, PYTHONPATH=sys.argv[1]), capture_output=True, text=True)
check("converter runs", run.returncode == 0 and "4 sizes x 9 wavelengths" in run.stdout,
      f"exit {run.returncode}: {run.stdout.strip()} {run.stderr.strip()}")

header = open(table).readline().split()
rows = np.loadtxt(table, skiprows=1)
expect = np.column_stack([np.repeat(sizes, len(lams)), np.tile(lams * 1e4, len(sizes)), k_abs.ravel(),
                          k_sca.ravel(), g.ravel()])
worst = float(np.max(np.abs(rows / np.where(expect == 0, 1, expect) - np.where(expect == 0, 0, 1))))
check("rows hold the npz values", header == ["4", "9"] and rows.shape == (36, 5) and worst < 1e-9,
      f"header {header}, rows {rows.shape}, largest relative difference {worst:.2e}")
check("negative g kept", rows[len(lams) - 1, 4] == -1.5e-6,
      f"g of the last row of the first size {rows[len(lams) - 1, 4]:g}")

deck = os.path.join(decks, "transition_disc_nonisothermal_ci.toml")
out = os.path.join(work, "run")
run = subprocess.run([exe, deck, "run.max_steps=2", f"output.dir={out}", "output.overwrite=true",
                      "radiation.opacity=dsharp", f"radiation.opacity_file={table}"], capture_output=True, text=True)
check("transition disc runs on the table", run.returncode == 0 and os.path.exists(os.path.join(out, "history.txt")),
      f"exit {run.returncode} {run.stderr.strip()[-200:]}")

bad = os.path.join(work, "not_dsharp.npz")
np.savez(bad, a=sizes, lam=lams)
run = subprocess.run([sys.executable, "-m", "mote.opacity_tables", "dsharp_opac", bad, table + ".bad"],
                     env=dict(os.environ, PYTHONPATH=sys.argv[1]), capture_output=True, text=True)
check("npz without the opacities refused", run.returncode == 1 and "k_abs, k_sca, g" in run.stderr
      and not os.path.exists(table + ".bad"), f"exit {run.returncode}: {run.stderr.strip()}")
run = subprocess.run([sys.executable, "-m", "mote.opacity_tables", "dsharp", npz],
                     env=dict(os.environ, PYTHONPATH=sys.argv[1]), capture_output=True, text=True)
check("bad command line refused", run.returncode == 2 and "usage" in run.stderr, f"exit {run.returncode}")

sys.exit(v.finish())
