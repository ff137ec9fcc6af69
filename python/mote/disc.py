"""Helpers for snapshots of the (R, theta) disc grid (the disc_* problems)."""
import numpy as np


def gas_state(snap):
    """Gas arrays of a disc-grid snapshot (its /data and /fields) plus the grid:
    R_edges, tan_te (tan theta edges) from the structured mesh nodes
    (x = R^e, y = R^e tan theta^e), theta_edges, R_c and theta_c (cell centres)."""
    out = dict(snap.data)
    out.update(snap.fields)
    x, y = np.asarray(snap.x_nodes), np.asarray(snap.y_nodes)
    out["R_edges"] = x[:, 0]
    out["tan_te"] = y[0, :] / x[0, :]
    out["theta_edges"] = np.arctan(out["tan_te"])
    out["R_c"] = snap.data["R_centres"]
    out["theta_c"] = snap.data["theta_centres"]
    return out
