#!/usr/bin/env python3
"""Gas disc on 2 and 3 MPI ranks (radial slabs; with 3 a middle slab) reproduces 1 rank
bit for bit (the slabs change no arithmetic), and a 2-rank checkpoint restarts on 1 rank
identically. The "user" gas boundary is refused on 2 ranks by a problem that
supplies no boundary values (exit 2 naming the key; before, the boundary rank
threw alone at the first gas step and the other rank waited for it forever).

usage: disc_gas_mpi.py VISCOUS_RING_EXE DISC_HYDROSTATIC_EXE WORKDIR MPIEXEC [ARGS ...]
"""
import os
import shutil
import sys

import numpy as np

from harness import MPI_ENV, Checks, run, run_within, with_ranks
import mote

ring_exe, hydro_exe, work, launcher = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
root = os.path.join(os.path.dirname(__file__), "..", "..", "problems")
shutil.rmtree(work, ignore_errors=True)
checks = Checks()
cases = {
    # user (analytic) boundaries, odd cell count
    "ring": (ring_exe, os.path.join(root, "viscous_ring", "viscous_ring.toml"),
             ["grid.nr=37", "run.t_end=20", "output.snapshot_dt=10"]),
    # evolving non-steady disc with power-law boundaries; exercises the velocity halo exchanges
    "hydro": (hydro_exe, os.path.join(root, "disc_hydrostatic", "disc_hydrostatic.toml"),
              ["grid.nr=41", "grid.ntheta=48", "gas.alpha=0.1", "gas.Sigma_index=0.5", "gas.R_c=4.0", "run.t_end=40",
               "output.snapshot_dt=20"]),
}
for name, (exe, deck, common) in cases.items():
    one, two, three, mixed = (os.path.join(work, f"{name}_{d}") for d in ("one", "two", "three", "mixed"))
    run([exe, deck, *common, f"output.dir={one}"])
    run(launcher + [exe, deck, *common, f"output.dir={two}"])
    run(with_ranks(launcher, 3) + [exe, deck, *common, f"output.dir={three}"])
    run(launcher + [exe, deck, *common, "run.max_steps=25", f"output.dir={mixed}"])
    run([exe, "--restart", "latest", deck, *common, f"output.dir={mixed}"])
    a, b, c = mote.last_snapshot(one), mote.last_snapshot(two), mote.last_snapshot(mixed)
    checks.check(a.step == b.step == c.step and a.step > 25, f"{name}: same number of steps ({a.step}, {b.step}, {c.step})")
    arrays = lambda s: {**s.data, **s.fields}  # noqa: E731
    A, B, C, T = arrays(a), arrays(b), arrays(c), arrays(mote.last_snapshot(three))
    for key in sorted(k for k in A if k.startswith("gas_")):
        x, y, z = A[key], B[key], C[key]
        scale = np.maximum(np.abs(x), 1e-300)
        diff = float(np.max(np.abs(x - y) / scale))
        bitwise = x.tobytes() == y.tobytes()
        checks.check(bitwise, f"{name} {key}: 2 ranks vs 1 rank bit for bit (max rel diff {diff:.1e})")
        checks.check(x.tobytes() == z.tobytes(), f"{name} {key}: 2-rank checkpoint restarted on 1 rank identical")
        checks.check(x.tobytes() == T[key].tobytes(), f"{name} {key}: 3 ranks vs 1 rank bit for bit")
hydro_deck = os.path.join(root, "disc_hydrostatic", "disc_hydrostatic.toml")
for side in ("inner", "outer"):
    rc, out = run_within([*launcher, hydro_exe, hydro_deck, f"gas.{side}_boundary=user",
                          f"output.dir={os.path.join(work, 'user_' + side)}"], 120, env=dict(os.environ, **MPI_ENV))
    expected = f"key 'gas.{side}_boundary'"
    checks.check(rc == 2 and expected in out and '"closed", "zero_torque", "extrapolate"' in out,
                 f"disc_hydrostatic, gas.{side}_boundary = user on 2 ranks: exit {rc} == 2 naming the key" +
                 ("" if rc == 2 and expected in out else f"\n{out[-1500:]}"))
sys.exit(checks.finish())
