"""Shared helpers for regression tests: running problem executables and
comparing their output. Each test script exits non-zero on failure and ends
with a line 'N passed, M failed'."""
import os
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "python"))

MPI_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1", "OMPI_MCA_rmaps_base_oversubscribe": "1"}


def checksums(directory, skip=()):
    """{file name: sha256} of every regular file in directory except those in skip (and symbolic links)."""
    import hashlib
    sums = {}
    for name in sorted(os.listdir(directory)):
        path = os.path.join(directory, name)
        if name not in skip and os.path.isfile(path) and not os.path.islink(path):
            with open(path, "rb") as f:
                sums[name] = hashlib.sha256(f.read()).hexdigest()
    return sums



def hdf5_datasets(path):
    """Every dataset of an HDF5 file as bytes, by name (for bit-for-bit comparisons)."""
    import h5py
    out = {}
    with h5py.File(path) as f:
        f.visititems(lambda name, obj: out.__setitem__(name, obj[...].tobytes())
                     if isinstance(obj, h5py.Dataset) else None)
    return out

def files(d, prefix, ext=".h5"):
    """Names of the files in d that start with prefix and end with ext, sorted."""
    return sorted(f for f in os.listdir(d) if f.startswith(prefix) and f.endswith(ext))


def unreadable_hdf5(d):
    """Names of the .h5 files in d that h5py cannot open (a file under a final name must be complete)."""
    import h5py
    bad = []
    for f in files(d, ""):
        try:
            h5py.File(os.path.join(d, f), "r").close()
        except OSError:
            bad.append(f)
    return bad


def run_within(cmd, time_limit, **kw):
    """Runs cmd (list; stderr into stdout) in a session of its own; returns (exit code, output), or (None, output)
    after killing the whole session (mpirun and its ranks) when it runs past time_limit seconds."""
    import signal
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True,
                         **kw)
    try:
        out = p.communicate(timeout=time_limit)[0]
        return p.returncode, out
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        return None, p.communicate()[0] + f"\n(killed after {time_limit} s)"


def with_ranks(launcher, ranks):
    """The MPI launcher (e.g. mpiexec -n 2 --oversubscribe) with its rank count replaced by `ranks`."""
    flags = ("-n", "-np", "--np", "-c", "--n")
    out = [str(ranks) if i > 0 and launcher[i - 1] in flags else x for i, x in enumerate(launcher)]
    if out == list(launcher):
        raise ValueError(f"no rank count in the launcher {launcher}")
    return out


def run(cmd, expect=0, extra_env=None, **kw):
    """Runs cmd (list) with extra_env added to the environment; returns CompletedProcess; raises if the exit
    code differs from expect."""
    env = dict(os.environ, **MPI_ENV, **(extra_env or {}))
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, **kw)
    if expect is not None and p.returncode != expect:
        raise AssertionError(f"{' '.join(cmd)} exited {p.returncode}, expected {expect}\nstdout:\n{p.stdout[-3000:]}\nstderr:\n{p.stderr[-3000:]}")
    return p


class Checks:
    """Collects named pass/fail results and prints a summary line."""

    def __init__(self):
        self.passed = 0
        self.failed = 0

    def check(self, ok, what):
        print(("PASS " if ok else "FAIL ") + what, flush=True)
        if ok:
            self.passed += 1
        else:
            self.failed += 1

    def finish(self):
        print(f"{self.passed} passed, {self.failed} failed")
        return 0 if self.failed == 0 and self.passed > 0 else 1


def fit_order(resolutions, errors):
    """Least-squares slope of log(error) against log(1/resolution)."""
    import numpy as np
    x = np.log(1.0 / np.asarray(resolutions, dtype=float))
    y = np.log(np.asarray(errors, dtype=float))
    return float(np.polyfit(x, y, 1)[0])


def check_conservation(checks, run_dir, energy_tol, momentum_tol=1e-12):
    """Mass conserved to 1e-12 relative, x momentum to momentum_tol of the run's momentum scale (the largest
    sum m |v| of the history; A7), total energy to energy_tol, from history.txt."""
    import mote
    h = mote.read_history(os.path.join(run_dir, "history.txt"))
    m0, p_scale = h["mass"][0], max(h["momentum_abs"])
    dp = abs(h["momentum_x"][-1] - h["momentum_x"][0])
    checks.check(abs(h["mass"][-1] - m0) <= 1e-12 * m0 and dp <= momentum_tol * p_scale,
                 f"mass to 1e-12, momentum to {momentum_tol:g} of sum m|v| (drift {dp / p_scale:.1e})")
    drift = abs(h["energy"][-1] - h["energy"][0]) / h["energy"][0]
    checks.check(drift < energy_tol, f"energy drift {drift:.1e} < {energy_tol:g}")
