"""The small runs whose snapshots the ParaView tests open (paraview_readers.py,
paraview_render.py): one of each output kind."""
import os

import numpy as np

from harness import ROOT, run

R_IN, R_OUT, THETA = 10.0, 50.0, 0.5235987755982988  # disc grid: R in [R_IN, R_OUT], theta in [-THETA, THETA]

# problem -> (output kind, deck overrides, field to colour by)
RUNS = {
    "gaussian_pulse": ("grid", ["grid.nx=24", "grid.ny=16", "run.t_end=0.2", "output.snapshot_dt=0.1"], "density"),
    "disc_pulse": ("grid", ["grid.nr=20", "grid.ntheta=12", f"grid.R_in={R_IN}", f"grid.R_out={R_OUT}",
                            f"grid.theta_min={-THETA}", f"grid.theta_max={THETA}", "run.t_end=0.3",
                            "output.snapshot_dt=0.15"], "dust_density"),
    "sph_dustydiffuse": ("particles", ["dustydiffuse.n=8", "run.t_end=0.01", "output.snapshot_dt=0.005"], "dust_fraction"),
}

# Analytic area of each grid: the unit square; the disc grid's nodes are (R, R tan theta), so its
# cells fill the sector between R_IN, R_OUT and the rays Z = R tan(+-THETA) exactly (straight edges).
AREA = {"gaussian_pulse": 1.0, "disc_pulse": 0.5 * (R_OUT**2 - R_IN**2) * 2.0 * np.tan(THETA)}


def run_problems(bindir, work):
    """Runs every problem of RUNS into work/<problem>; returns {problem: output directory}."""
    dirs = {}
    for problem, (_, args, _) in RUNS.items():
        out = os.path.join(work, problem)
        deck = os.path.join(ROOT, "problems", problem, problem + ".toml")
        run([os.path.join(bindir, problem), deck, f"output.dir={out}", "run.progress_interval=0"] + args)
        dirs[problem] = out
    return dirs


def snapshots(out):
    return sorted(os.path.join(out, f) for f in os.listdir(out) if f.startswith("snapshot_") and f.endswith(".h5"))
