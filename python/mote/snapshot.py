"""Reader for mote HDF5 snapshots and checkpoints (layout: include/mote/io/snapshot.hpp)."""
import glob
import os

import h5py
import numpy as np


def _text(value):
    return value.decode("utf-8") if isinstance(value, (bytes, np.bytes_)) else str(value)


class Snapshot:
    """One snapshot: root attributes, mesh coordinates and fields as numpy arrays.

    Attributes: path, time, step, problem, deck (resolved TOML text), units
    (dict: system, length_cm, mass_g, time_s), x_nodes, y_nodes, xy_nodes (the
    nodes as (ny + 1, nx + 1, 2), as the XDMF descriptor gives them), x, y (cell
    centres), fields (name -> array), data (other arrays, name -> array), field_units (name -> (label, to_cgs)).
    """

    def __init__(self, path):
        self.path = path
        with h5py.File(path, "r") as f:
            a = f.attrs
            self.time = float(a["time"])
            self.step = int(a["step"])
            self.problem = _text(a["problem"])
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
            self.fields = {}
            self.field_units = {}
            if "fields" in f:
                for name, ds in f["fields"].items():
                    self.fields[name] = ds[...]
                    self.field_units[name] = (_text(ds.attrs.get("unit", "")), float(ds.attrs.get("to_cgs", 1.0)))
            self.data = {name: ds[...] for name, ds in f["data"].items()} if "data" in f else {}
            self.state = {name: ds[...] for name, ds in f["state"].items()} if "state" in f else {}

    @property
    def x(self):
        return None if self.x_nodes is None else 0.5 * (self.x_nodes[1:] + self.x_nodes[:-1])

    @property
    def y(self):
        return None if self.y_nodes is None else 0.5 * (self.y_nodes[1:] + self.y_nodes[:-1])

    def cgs(self, name):
        """Field `name` converted to cgs with its stored factor."""
        return self.fields[name] * self.field_units[name][1]

    def __repr__(self):
        return f"Snapshot({self.path!r}, t={self.time:g}, step={self.step}, fields={sorted(self.fields)})"


def read_snapshot(path):
    return Snapshot(path)


def list_snapshots(directory):
    """Snapshot files of a run directory, in order."""
    return sorted(glob.glob(os.path.join(directory, "snapshot_*.h5")))


def last_snapshot(directory):
    files = list_snapshots(directory)
    if not files:
        raise FileNotFoundError(f"no snapshot_*.h5 in {directory}")
    return Snapshot(files[-1])
