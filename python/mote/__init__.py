"""mote: read snapshots, checkpoints and history files of mote runs into numpy.

    import mote
    snap = mote.read_snapshot("runs/gaussian_pulse/snapshot_00004.h5")
    snap.time, snap.fields["density"], snap.x_nodes, snap.deck
    hist = mote.read_history("runs/gaussian_pulse/history.txt")
    hist["time"], hist["mass"]
    dump = mote.read_phantom("runs/sph_dustybox/snapshot_00001.phantom")  # output.sph_format
    dump.header["massoftype"], dump.arrays["x"], dump.arrays["itype"]
"""
__version__ = "0.1.0"  # = python/pyproject.toml and project(mote VERSION)

from .snapshot import Snapshot, read_snapshot, list_snapshots, last_snapshot
from .history import read_history
from .disc import gas_state
from .phantom import PhantomDump, read_phantom

__all__ = ["Snapshot", "read_snapshot", "list_snapshots", "last_snapshot", "read_history", "gas_state",
           "PhantomDump", "read_phantom"]
