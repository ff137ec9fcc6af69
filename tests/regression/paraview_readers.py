#!/usr/bin/env python3
"""ParaView opens every kind of mote output correctly with both of its XDMF
readers (the legacy "XDMF Reader" and Xdmf3, Xdmf3ReaderS and Xdmf3ReaderT),
headless under pvbatch: a small run of gaussian_pulse (Cartesian grid),
disc_pulse (the (R, theta) disc grid, curvilinear nodes) and sph_dustydiffuse
(3D SPH point cloud). For the last snapshot of each, and for the run's
snapshots.xmf time series, tests/paraview/probe.py reports what the reader
built; this script compares it with the HDF5 file (h5py):
- cell and point counts, bounds (the node or particle coordinates), array
  names, components and value ranges;
- grids: the area of ExtractSurface + IntegrateVariables against the analytic
  area of the domain (unit square; for the disc grid the sector between R_in,
  R_out and the rays Z = R tan(theta_min), Z = R tan(theta_max), exactly
  (R_out^2 - R_in^2) / 2 * (tan theta_max - tan theta_min) since the cell edges
  are straight), the integral of each field against sum(field * cell area)
  (ExtractSurface's points are single precision: relative errors of 1e-9 in
  the area and 1e-7 in the integrals are seen, hence 1e-6 and 1e-5),
  and the value of every cell against the HDF5 cell with the same centre;
- snapshots.xmf: one time step per snapshot at the snapshots' times, and its
  last step is the last snapshot.

usage: paraview_readers.py PVBATCH BINDIR WORKDIR
"""
import json
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

from harness import ROOT, Checks
from paraview_runs import AREA, RUNS, run_problems, snapshots

pvbatch, bindir, work = sys.argv[1], sys.argv[2], sys.argv[3]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
PROBE = os.path.join(ROOT, "tests", "paraview", "probe.py")
READERS = ["legacy", "xdmf3s", "xdmf3t"]
checks = Checks()


def close(a, b, rtol=1e-12, atol=1e-300):
    return bool(np.allclose(np.asarray(a, float), np.asarray(b, float), rtol=rtol, atol=atol))


def probe(xmf, reader, field=None):
    cmd = [pvbatch, PROBE, xmf, reader] + ([field] if field else [])
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    lines = [l for l in p.stdout.splitlines() if l.startswith("PROBE ")]
    if p.returncode != 0 or not lines:
        tail = (p.stdout + p.stderr).strip().splitlines()[-3:]
        return None, f"pvbatch exited {p.returncode}: {' | '.join(tail)}"
    return json.loads(lines[-1][6:]), ""


def quad_areas(xy):
    """Areas of the quadrilateral cells of a (ny+1, nx+1, 2) node array (shoelace)."""
    a, b, c, d = xy[:-1, :-1], xy[:-1, 1:], xy[1:, 1:], xy[1:, :-1]
    ring = [a, b, c, d, a]
    s = sum(ring[k][..., 0] * ring[k + 1][..., 1] - ring[k + 1][..., 0] * ring[k][..., 1] for k in range(4))
    return 0.5 * np.abs(s)


def check_grid(name, got, h5path, tag):
    with h5py.File(h5path, "r") as f:
        xy = f["mesh/xy_nodes"][...]
        fields = {k: v[...] for k, v in f["fields"].items()}
    ny, nx = xy.shape[0] - 1, xy.shape[1] - 1
    # the interleaved nodes are the ones the HDF5 file also holds as x_nodes/y_nodes
    checks.check(got["cells"] == nx * ny and got["points"] == (nx + 1) * (ny + 1),
                 f"{tag}: {got['cells']} cells, {got['points']} points (HDF5: {nx} x {ny} cells)")
    want = [xy[..., 0].min(), xy[..., 0].max(), xy[..., 1].min(), xy[..., 1].max(), 0.0, 0.0]
    checks.check(close(got["bounds"], want), f"{tag}: bounds {np.round(got['bounds'], 6).tolist()} = HDF5 nodes' bounds")
    checks.check(got["cell_arrays"] == {k: 1 for k in fields},
                 f"{tag}: cell arrays {sorted(got['cell_arrays'])} = HDF5 /fields {sorted(fields)}")
    ranges_ok = all(k in got["cell_ranges"] and close(got["cell_ranges"][k], [v.min(), v.max()]) for k, v in fields.items())
    checks.check(ranges_ok, f"{tag}: every field's value range = HDF5's")
    area = got["integrals"].get("Area", 0.0)
    checks.check(close(area, AREA[name], rtol=1e-6),
                 f"{tag}: surface area {area:.12g} = analytic {AREA[name]:.12g} (rel. error {abs(area / AREA[name] - 1):.1e})")
    cell_area = quad_areas(xy)
    errors = [abs(got["integrals"].get(k, np.nan) / (v * cell_area).sum() - 1) for k, v in fields.items()]
    checks.check(max(errors) < 1e-5,
                 f"{tag}: integral of every field = HDF5 sum(field * cell area) (max rel. error {max(errors):.1e} < 1e-5)")
    field = sorted(fields)[0]
    centres = 0.25 * (xy[:-1, :-1] + xy[:-1, 1:] + xy[1:, 1:] + xy[1:, :-1]).reshape(-1, 2)
    vc = np.asarray(got.get("cell_centres", []), float)
    vv = np.asarray(got.get("cell_values", []), float)
    ok = vc.shape == (nx * ny, 3) and vv.shape == (nx * ny,)
    if ok:
        nearest = np.argmin(((vc[:, None, :2] - centres[None, :, :]) ** 2).sum(-1), axis=1)
        ok = len(set(nearest.tolist())) == nx * ny and close(vv, fields[field].reshape(-1)[nearest])
    checks.check(ok, f"{tag}: every cell's '{field}' is the HDF5 value of the cell with that centre")


def check_particles(got, h5path, tag):
    with h5py.File(h5path, "r") as f:
        pos = f["particles/position"][...]
        arrays = {k: v[...] for k, v in f["particles"].items() if k != "position"}
    n = pos.shape[0]
    checks.check(got["points"] == n and got["cells"] == n, f"{tag}: {got['points']} points, {got['cells']} vertex cells (HDF5: {n} particles)")
    want = np.ravel(np.column_stack([pos.min(0), pos.max(0)]))
    checks.check(close(got["bounds"], want), f"{tag}: bounds {np.round(got['bounds'], 6).tolist()} = HDF5 positions' bounds")
    comps = {k: (1 if v.ndim == 1 else v.shape[1]) for k, v in arrays.items()}
    checks.check(got["point_arrays"] == comps, f"{tag}: point arrays {sorted(got['point_arrays'])} with HDF5's components")
    mags = {k: (np.linalg.norm(v, axis=1) if v.ndim > 1 else v) for k, v in arrays.items()}
    ranges_ok = all(k in got["point_ranges"] and close(got["point_ranges"][k], [v.min(), v.max()]) for k, v in mags.items())
    checks.check(ranges_ok, f"{tag}: every array's value range = HDF5's (vectors: of the magnitude)")


dirs = run_problems(bindir, work)
for problem, (kind, _, _) in RUNS.items():
    out = dirs[problem]
    snaps = snapshots(out)
    checks.check(len(snaps) == 3, f"{problem}: 3 snapshots (got {len(snaps)})")
    last = snaps[-1]
    with h5py.File(last, "r") as f:
        field = sorted(f["fields"])[0] if "fields" in f else None
    times = []
    for s in snaps:
        with h5py.File(s, "r") as f:
            times.append(float(f.attrs["time"]))
    for reader in READERS:
        for xmf in (last[:-3] + ".xmf", os.path.join(out, "snapshots.xmf")):
            series = xmf.endswith("snapshots.xmf")
            tag = f"{problem} {os.path.basename(xmf)} [{reader}]"
            got, error = probe(xmf, reader, field if kind == "grid" else None)
            checks.check(got is not None, f"{tag}: opened {error}")
            if got is None:
                continue
            if series:
                checks.check(close(got["times"], times, rtol=1e-14), f"{tag}: time steps {got['times']} = the snapshots' times")
            if kind == "grid":
                check_grid(problem, got, last, tag)
            else:
                check_particles(got, last, tag)

sys.exit(checks.finish())
