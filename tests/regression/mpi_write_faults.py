#!/usr/bin/env python3
"""Write errors on 2 MPI ranks stop every rank together (issue 22, "every write is checked").

    mpi_write_faults.py EXE WORKDIR LAUNCHER...

Runs gaussian_pulse (16 x 16) on 2 ranks and makes a write fail; each case
must end within a time limit (no rank left waiting for the other), with exit
code 5 from mpirun, exactly one error line naming the file and the system
error, no HDF5 error stack, no temporary or incomplete file under a final
name, no lock left, and the earlier files unchanged (checksums):
  * a snapshot that exceeds the file-size limit (RLIMIT_FSIZE) of rank 0 alone,
    the rank that writes the files, and of both ranks: a checkpoint of the state
    is written before stopping, and the run restarts from it on 2 ranks;
  * a limit below a checkpoint's size: no checkpoint either, the earlier ones restart;
  * a checkpoint's, the history's, an XDMF file's and snapshots.xmf's temporary on
    /dev/full;
  * a small tmpfs filling up (only where this process may mount one, else skipped).
Ends with 'N passed, M failed'.
"""
import os
import resource
import shutil
import signal
import subprocess
import sys


from harness import MPI_ENV, Checks, checksums, files, run_within, unreadable_hdf5

IO_ERROR = 5  # docs/quickstart.md, include/mote/core/exit_codes.hpp
TIME_LIMIT = 60  # seconds; a run still going then has ranks waiting for each other
LIMIT_OPTION = "--file-size-limit"


def exec_with_file_size_limit(ranks, limit, cmd):
    """Runs as the rank process: applies RLIMIT_FSIZE `limit` where this rank is in `ranks`, then execs cmd."""
    if ranks == "all" or os.environ.get("OMPI_COMM_WORLD_RANK") in ranks.split(","):
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    os.execv(cmd[0], cmd)


if len(sys.argv) > 1 and sys.argv[1] == LIMIT_OPTION:
    exec_with_file_size_limit(sys.argv[2], int(sys.argv[3]), sys.argv[4:])

exe, work, launcher = sys.argv[1], sys.argv[2], sys.argv[3:]
deck = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "problems", "gaussian_pulse",
                                    "gaussian_pulse.toml"))
common = ["grid.nx=16", "grid.ny=16", "output.checkpoint_every=4", "output.checkpoints_kept=10",
          "run.progress_interval=0"]
HDF5_NOISE = ["HDF5-DIAG", "infinite loop closing library", "#000:", "H5Dwrite", "Segmentation fault"]
# Open MPI's shared-memory transport and PMIx keep their data in files, which a file-size limit would break.
ENV = dict(os.environ, **MPI_ENV, PMIX_MCA_gds="hash", OMPI_MCA_btl="self,tcp")
checks = Checks()


def mpirun(args, limit=None):
    """Runs exe on 2 ranks with args (under a file-size limit (ranks, bytes) if given); returns (rc, output)."""
    wrapper = [sys.executable, os.path.abspath(__file__), LIMIT_OPTION, limit[0], str(limit[1])] if limit else []
    return run_within([*launcher, *wrapper, exe, *args], TIME_LIMIT, env=ENV, cwd=work)


def fresh_run(name):
    """A 2-rank run of 6 steps (checkpoints at steps 4 and 6) into WORKDIR/name; returns the directory."""
    d = os.path.join(work, name)
    rc, text = mpirun([deck, *common, f"output.dir={d}", "run.max_steps=6"])
    if rc != 0:
        raise AssertionError(f"the first part of {name} exited {rc}\n{text[-3000:]}")
    return d


def restart_args(d, *extra):
    return ["--restart", "latest", deck, *common, f"output.dir={d}", "output.checkpoint_every=0", *extra]


def case(name, d, args, expected, limit=None, absent=(), skip=("history.txt",)):
    """Runs a failing 2-rank restart in d; checks exit 5, one error line holding every `expected` text and
    none of `absent`, no HDF5 noise, no temporary, no lock, and that the files of d (but `skip`) keep their
    bytes. Returns the checkpoints written by the run."""
    before, ckpts = checksums(d, skip), files(d, "checkpoint_")
    rc, text = mpirun(args, limit)
    checks.check(rc == IO_ERROR, f"{name}: mpirun exits {rc} == 5" + ("" if rc == IO_ERROR else f"\n{text[-3000:]}"))
    errors = [line for line in text.splitlines() if "error: " in line]
    checks.check(len(errors) == 1, f"{name}: one error line ({errors})")
    for e in expected:
        checks.check(e in text, f"{name}: message contains {e!r}" + ("" if e in text else f"\n{text[-3000:]}"))
    for e in [*HDF5_NOISE, *absent]:
        checks.check(e not in text, f"{name}: output does not contain {e!r}")
    left = [f for f in os.listdir(d) if f.endswith(".tmp") or f == "run.lock"]
    checks.check(not left, f"{name}: no temporary or lock file left ({left})")
    after = checksums(d, skip)
    checks.check({n: s for n, s in after.items() if n in before} == before and set(before) <= set(after),
                 f"{name}: earlier files unchanged")
    return [f for f in files(d, "checkpoint_") if f not in ckpts]


def restarts(name, d, checkpoint=None):
    rc, text = mpirun(["--restart", "latest", deck, *common, f"output.dir={d}"])
    ok = rc == 0 and (checkpoint is None or f"restarted from {os.path.join(d, checkpoint)}" in text)
    checks.check(ok, f"{name}: the run restarts on 2 ranks from {checkpoint or 'its last checkpoint'} and finishes"
                 + ("" if ok else f" (exit {rc})\n{text[-3000:]}"))


def snapshot_too_large(ranks):
    """A file-size limit between a checkpoint's and a snapshot's size on `ranks`: the snapshot fails, the
    checkpoint of the state is written."""
    name = f"snapshot beyond the file-size limit of rank(s) {ranks}"
    d = fresh_run(f"snapshot_{ranks}")
    ckpt = os.path.getsize(os.path.join(d, files(d, "checkpoint_")[-1]))
    snap = os.path.getsize(os.path.join(d, files(d, "snapshot_")[-1]))
    next_snapshot = f"snapshot_{len(files(d, 'snapshot_')):05d}.h5"
    new = case(name, d, restart_args(d), [f"error: cannot write '{d}/{next_snapshot}.tmp': File too large",
                                          "writing a checkpoint before stopping"], limit=(ranks, (ckpt + snap) // 2))
    checks.check(not os.path.exists(os.path.join(d, next_snapshot)), f"{name}: no snapshot under its final name")
    checks.check(len(new) == 1, f"{name}: a checkpoint of the state was written before stopping ({new})")
    restarts(name, d, new[0] if new else None)


def nothing_fits():
    """A limit below a checkpoint's size on both ranks: snapshot and checkpoint fail; the old ones remain."""
    name = "no checkpoint fits"
    d = fresh_run("nothing_fits")
    last = files(d, "checkpoint_")[-1]
    ckpt = os.path.getsize(os.path.join(d, last))
    new = case(name, d, restart_args(d), ["File too large", "the checkpoint could not be written either",
                                          f"the last checkpoint is {os.path.join(d, last)}"], limit=("all", ckpt - 1000))
    checks.check(not new, f"{name}: no new checkpoint ({new})")
    restarts(name, d, last)


def on_dev_full(name, d, temporary, args, expected, absent=()):
    os.symlink("/dev/full", os.path.join(d, temporary))
    new = case(name, d, args, expected, absent=absent, skip=("history.txt", temporary))
    checks.check(not os.path.lexists(os.path.join(d, temporary)), f"{name}: the temporary is removed")
    return new


def dev_full():
    """Temporaries on /dev/full: a checkpoint's (no second try), the history's, an XDMF file's, snapshots.xmf's."""
    d = fresh_run("dev_full_checkpoint")
    ckpt = f"checkpoint_{len(files(d, 'checkpoint_')) + 1:05d}.h5"
    new = on_dev_full("checkpoint on /dev/full", d, ckpt + ".tmp", restart_args(d, "output.checkpoint_every=2"),
                      [f"error: cannot write '{d}/{ckpt}.tmp': No space left on device"],
                      absent=["writing a checkpoint"])
    checks.check(not new, f"checkpoint on /dev/full: no checkpoint under its final name ({new})")
    d = fresh_run("dev_full_history")
    on_dev_full("history on /dev/full", d, "history.txt.tmp", restart_args(d),
                [f"error: cannot write '{d}/history.txt.tmp': No space left on device"])
    d = fresh_run("dev_full_xdmf")
    xmf = f"snapshot_{len(files(d, 'snapshot_')):05d}.xmf"
    new = on_dev_full("XDMF on /dev/full", d, xmf + ".tmp", restart_args(d),
                      [f"error: cannot write '{d}/{xmf}.tmp': No space left on device", "writing a checkpoint"])
    checks.check(len(new) == 1 and not os.path.exists(os.path.join(d, xmf)),
                 f"XDMF on /dev/full: a checkpoint written ({new}), no {xmf}")
    d = fresh_run("dev_full_series")
    new = on_dev_full("snapshots.xmf on /dev/full", d, "snapshots.xmf.tmp", restart_args(d),
                      [f"error: cannot write '{d}/snapshots.xmf.tmp': No space left on device", "writing a checkpoint"])
    checks.check(len(new) == 1, f"snapshots.xmf on /dev/full: a checkpoint written ({new})")


def small_tmpfs():
    """A 192 KiB tmpfs filling up during a 2-rank run: exit 5, no .tmp, every .h5 left readable."""
    d = os.path.join(work, "tmpfs")
    os.makedirs(d)
    if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=192k", "tmpfs", d], capture_output=True).returncode != 0:
        print("SKIP small tmpfs: cannot mount one here (needs root); the file-size limit and /dev/full cases cover "
              "full disks")
        return
    try:
        case("tmpfs full", d, [deck, *common, f"output.dir={d}", "grid.nx=48", "grid.ny=48",
                               "output.checkpoint_every=2"], ["No space left on device"])
        bad = unreadable_hdf5(d)
        checks.check(not bad, f"tmpfs full: every .h5 under a final name is readable ({bad})")
    finally:
        subprocess.run(["umount", d])


def main():
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    snapshot_too_large("0")
    snapshot_too_large("all")
    nothing_fits()
    dev_full()
    small_tmpfs()
    shutil.rmtree(work, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
