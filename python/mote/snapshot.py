"""Reader for mote HDF5 snapshots and checkpoints (layout: docs/output.md)."""
import glob
import os
import re

import h5py
import numpy as np


def _text(value):
    return value.decode("utf-8") if isinstance(value, (bytes, np.bytes_)) else str(value)


def _arrays_with_units(group):
    """({name: array}, {name: (unit label, to_cgs)}) of the datasets directly in `group`."""
    arrays, units = {}, {}
    for name, ds in group.items():
        if isinstance(ds, h5py.Dataset):
            arrays[name] = ds[...]
            units[name] = (_text(ds.attrs.get("unit", "")), float(ds.attrs.get("to_cgs", 1.0)))
    return arrays, units


def _all_datasets(group):
    """{path below `group`: array} of every dataset at any depth (a checkpoint's /state holds groups)."""
    found = {}
    group.visititems(lambda name, obj: found.__setitem__(name, obj[...]) if isinstance(obj, h5py.Dataset) else None)
    return found


class Snapshot:
    """One snapshot or checkpoint: root attributes, mesh coordinates and data as numpy arrays.

    Attributes: path, time, step, problem, run_id, code, deck (resolved TOML text), units (dict:
    system, length_cm, mass_g, time_s), x_nodes, y_nodes, xy_nodes (the nodes as one (rows + 1,
    cols + 1, 2) array, as the XDMF descriptor gives them), x, y (cell centres, see below),
    fields (grid cell data, name -> array), field_units (name -> (label, to_cgs)), data (other
    arrays) and data_units, particles (SPH particle data in id order, name -> array) and
    particle_units, state (a checkpoint's state: path below /state, e.g. "gas/Sigma" -> array).

    Cell centres: on the Cartesian grid x (nx) and y (ny), the midpoints of the 1D nodes; on the
    (R, theta) disc grid x and y have the fields' shape (nr, ntheta): R_c and R_c tan(theta_c) of
    the grid's centres (/data/R_centres, /data/theta_centres).
    """

    def __init__(self, path):
        self.path = path
        with h5py.File(path, "r") as f:
            a = f.attrs
            self.time = float(a["time"])
            self.step = int(a["step"])
            self.problem = _text(a["problem"])
            self.run_id = _text(a["run_id"]) if "run_id" in a else None
            self.code = _text(a["code"]) if "code" in a else None
            self.deck = _text(a["deck"])
            self.units = {
                "system": _text(a["unit_system"]),
                "length_cm": float(a["unit_length_cm"]),
                "mass_g": float(a["unit_mass_g"]),
                "time_s": float(a["unit_time_s"]),
            }
            self.x_nodes = f["mesh/x_nodes"][...] if "mesh/x_nodes" in f else None
            self.y_nodes = f["mesh/y_nodes"][...] if "mesh/y_nodes" in f else None
            self.xy_nodes = f["mesh/xy_nodes"][...] if "mesh/xy_nodes" in f else None
            self.fields, self.field_units = _arrays_with_units(f["fields"]) if "fields" in f else ({}, {})
            self.data, self.data_units = _arrays_with_units(f["data"]) if "data" in f else ({}, {})
            self.particles, self.particle_units = _arrays_with_units(f["particles"]) if "particles" in f else ({}, {})
            self.state = _all_datasets(f["state"]) if "state" in f else {}

    def _disc_centres(self):
        R, theta = self.data.get("R_centres"), self.data.get("theta_centres")
        if R is not None and theta is not None:
            return np.outer(R, np.ones_like(theta)), np.outer(R, np.tan(theta))
        corners = lambda n: 0.25 * (n[1:, 1:] + n[:-1, 1:] + n[1:, :-1] + n[:-1, :-1])  # noqa: E731
        return corners(self.x_nodes), corners(self.y_nodes)

    @property
    def x(self):
        if self.x_nodes is None:
            return None
        if self.x_nodes.ndim == 2:
            return self._disc_centres()[0]
        return 0.5 * (self.x_nodes[1:] + self.x_nodes[:-1])

    @property
    def y(self):
        if self.y_nodes is None:
            return None
        if self.y_nodes.ndim == 2:
            return self._disc_centres()[1]
        return 0.5 * (self.y_nodes[1:] + self.y_nodes[:-1])

    def cgs(self, name):
        """Field, array or particle quantity `name` converted to cgs with its stored factor."""
        for values, units in ((self.fields, self.field_units), (self.data, self.data_units),
                              (self.particles, self.particle_units)):
            if name in values:
                return values[name] * units[name][1]
        raise KeyError(name)

    def __repr__(self):
        kind = f"particles={len(next(iter(self.particles.values()), []))}" if self.particles else \
            f"fields={sorted(self.fields)}"
        return f"Snapshot({self.path!r}, t={self.time:g}, step={self.step}, {kind})"


def read_snapshot(path):
    return Snapshot(path)


_NUMBERED = re.compile(r"snapshot_(\d+)\.h5$")


def list_snapshots(directory):
    """Snapshot files of a run directory in the order of their numbers (not as text: snapshot_100000
    follows snapshot_99999); temporaries and superseded_NNNNN/ are not listed."""
    files = [f for f in glob.glob(os.path.join(glob.escape(directory), "snapshot_*.h5")) if _NUMBERED.search(f)]
    return sorted(files, key=lambda f: int(_NUMBERED.search(f).group(1)))


def last_snapshot(directory):
    files = list_snapshots(directory)
    if not files:
        raise FileNotFoundError(f"no snapshot_*.h5 in {directory}")
    return Snapshot(files[-1])
