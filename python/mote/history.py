"""Reader for mote history files (include/mote/io/history.hpp)."""
import numpy as np


def read_history(path):
    """History as a numpy structured array; columns step, time, dt and the diagnostics."""
    with open(path) as f:
        header = f.readline()
    if not header.startswith("#"):
        raise ValueError(f"{path}: no header line")
    names = header[1:].split()
    data = np.loadtxt(path, comments="#", ndmin=2)
    if data.size == 0:  # the header alone: no row yet
        data = np.zeros((0, len(names)))
    if data.shape[1] != len(names):
        raise ValueError(f"{path}: {data.shape[1]} columns in the rows but {len(names)} names in the header")
    out = np.zeros(data.shape[0], dtype=[(n, np.int64 if n == "step" else np.float64) for n in names])
    for i, n in enumerate(names):
        out[n] = data[:, i]
    return out
