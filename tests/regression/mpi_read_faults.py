#!/usr/bin/env python3
"""A checkpoint that one MPI rank alone cannot read, or reads differently, is judged alike on every rank
(issue 22).

    mpi_read_faults.py EXE WORKDIR LAUNCHER...

Runs gaussian_pulse (16 x 16) on 2 ranks. Every case must end within a time limit (no rank left waiting
for the other).
  * Unreadable on rank 1: rank 1 runs without the capabilities that let root read any file (setpriv
    --bounding-set -dac_override,-dac_read_search), and the newest checkpoint belongs to user nobody with
    mode 0600. --restart latest skips it on both ranks, naming rank 1 and the system error, and restarts
    from the previous one; --restart FILE of it stops both ranks with exit 2 and one error line naming
    rank 1 and the system error, the files unchanged (checksums).
  * Not HDF5 on rank 1: rank 1 runs in a mount namespace of its own (unshare -m) where a file of zeros is
    bound over the newest checkpoint: open() succeeds on both ranks, and so does H5Fopen (parallel HDF5
    1.10 reads the superblock on rank 0 for every rank), but the ranks then read different lists of the
    state's datasets. --restart latest skips the checkpoint on both ranks, saying that the ranks do not
    see the same file, and restarts from the previous one; --restart FILE exits 2 with one error line.
Skipped where this process is not root, setpriv is missing or unshare -m fails. Ends with 'N passed, M
failed'.
"""
import os
import shutil
import sys

from harness import MPI_ENV, Checks, checksums, run_within

BAD_INPUT = 2  # docs/quickstart.md, include/mote/core/exit_codes.hpp
TIME_LIMIT = 60  # seconds; a run still going then has ranks waiting for each other
RANK1_OPTION = "--as-rank"
SETPRIV = "/usr/bin/setpriv"
UNSHARE = "/usr/bin/unshare"
RANK1_VIEW = "MOTE_TEST_RANK1_VIEW"  # "SOURCE:TARGET": rank 1 alone sees SOURCE's bytes at TARGET

if len(sys.argv) > 1 and sys.argv[1] == RANK1_OPTION:  # runs as a rank process
    cmd = sys.argv[2:]
    if os.environ.get("OMPI_COMM_WORLD_RANK") == "1":
        view = os.environ.get(RANK1_VIEW)
        if view:
            source, target = view.split(":")
            cmd = [UNSHARE, "-m", "sh", "-c", 'mount --bind "$0" "$1" && shift && exec "$@"', source, target, *cmd]
        else:
            cmd = [SETPRIV, "--bounding-set", "-dac_override,-dac_read_search", *cmd]
    os.execv(cmd[0], cmd)

exe, work, launcher = sys.argv[1], sys.argv[2], sys.argv[3:]
deck = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "problems", "gaussian_pulse",
                                    "gaussian_pulse.toml"))
common = [deck, "grid.nx=16", "grid.ny=16", "output.checkpoint_every=4", "output.checkpoints_kept=10",
          "run.progress_interval=0"]
ENV = dict(os.environ, **MPI_ENV, PMIX_MCA_gds="hash", OMPI_MCA_btl="self,tcp")
checks = Checks()


def mpirun(args, rank1_view=None):
    env = dict(ENV, **({RANK1_VIEW: ":".join(rank1_view)} if rank1_view else {}))
    return run_within([*launcher, sys.executable, os.path.abspath(__file__), RANK1_OPTION, exe, *args], TIME_LIMIT,
                      env=env, cwd=work)


def first_run(name):
    """A 2-rank run of 8 steps into WORKDIR/name; returns (directory, its checkpoints, oldest first)."""
    d = os.path.join(work, name)
    rc, text = mpirun([*common, f"output.dir={d}", "run.max_steps=8"])
    if rc != 0:
        raise AssertionError(f"the first part of {name} exited {rc}\n{text[-3000:]}")
    return d, [os.path.join(d, f) for f in sorted(f for f in os.listdir(d) if f.startswith("checkpoint_"))]


def zeros_like(path):
    """A file of zeros as long as `path` (beside WORKDIR's runs): readable, but not HDF5."""
    zeros = os.path.join(work, "zeros_" + os.path.basename(path))
    with open(zeros, "wb") as f:
        f.write(bytes(os.path.getsize(path)))
    return zeros


def not_hdf5_on_rank1():
    d, ckpts = first_run("not_hdf5")
    newest, view = ckpts[-1], (zeros_like(ckpts[-1]), ckpts[-1])
    different = f"the ranks read different lists of the datasets under /state from '{newest}': they do not see " \
                "the same file"
    rc, text = mpirun(["--restart", "latest", *common, f"output.dir={d}", "run.max_steps=10"], view)
    checks.check(rc == 0, f"not HDF5 on rank 1, --restart latest: exits {rc} == 0" +
                 ("" if rc == 0 else f"\n{text[-3000:]}"))
    checks.check(f"skipping checkpoint '{newest}': it cannot be read: {different}" in text,
                 f"not HDF5 on rank 1, --restart latest: skips {os.path.basename(newest)}, the ranks reading "
                 "different lists of datasets")
    checks.check(f"restarted from {ckpts[-2]}" in text,
                 f"not HDF5 on rank 1, --restart latest: restarts from {os.path.basename(ckpts[-2])}")
    before = checksums(d)
    rc, text = mpirun(["--restart", newest, *common, f"output.dir={d}"], view)
    errors = [line for line in text.splitlines() if "error: " in line]
    checks.check(rc == BAD_INPUT, f"not HDF5 on rank 1, --restart FILE: exits {rc} == 2" +
                 ("" if rc == BAD_INPUT else f"\n{text[-3000:]}"))
    checks.check(len(errors) == 1 and different in errors[0],
                 f"not HDF5 on rank 1, --restart FILE: one error line saying so ({errors})")
    checks.check(checksums(d) == before, "not HDF5 on rank 1, --restart FILE: files unchanged")


def unshare_works():
    return os.path.exists(UNSHARE) and run_within([UNSHARE, "-m", "true"], 10)[0] == 0


def run_with_unreadable_newest(name):
    """A 2-rank run of 8 steps into WORKDIR/name whose newest checkpoint rank 1 cannot read; returns
    (directory, older checkpoints, the unreadable one)."""
    d, ckpts = first_run(name)
    newest = ckpts[-1]
    os.chown(newest, 65534, 65534)  # nobody
    os.chmod(newest, 0o600)
    return d, [os.path.basename(c) for c in ckpts[:-1]], newest


def restart_latest():
    d, older, newest = run_with_unreadable_newest("latest")
    rc, text = mpirun(["--restart", "latest", *common, f"output.dir={d}", "run.max_steps=10"])
    reason = f"on rank 1: cannot open '{newest}': Permission denied"
    checks.check(rc == 0, f"--restart latest: exits {rc} == 0" + ("" if rc == 0 else f"\n{text[-3000:]}"))
    checks.check(f"skipping checkpoint '{newest}'" in text and reason in text,
                 f"--restart latest: skips {os.path.basename(newest)} naming {reason!r}")
    checks.check(f"restarted from {os.path.join(d, older[-1])}" in text,
                 f"--restart latest: restarts from the previous checkpoint {older[-1]}")


def restart_file():
    d, _, newest = run_with_unreadable_newest("file")
    before = checksums(d)
    rc, text = mpirun(["--restart", newest, *common, f"output.dir={d}"])
    checks.check(rc == BAD_INPUT, f"--restart FILE: exits {rc} == 2" + ("" if rc == BAD_INPUT else f"\n{text[-3000:]}"))
    errors = [line for line in text.splitlines() if "error: " in line]
    checks.check(len(errors) == 1 and f"on rank 1: cannot open '{newest}': Permission denied" in errors[0],
                 f"--restart FILE: one error line naming rank 1 and the system error ({errors})")
    checks.check(checksums(d) == before, "--restart FILE: files unchanged")


def main():
    if os.geteuid() != 0 or not os.path.exists(SETPRIV) or not unshare_works():
        print("SKIP: needs root, setpriv and unshare -m to give one rank alone another view of a file")
        return 0
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    restart_latest()
    restart_file()
    not_hdf5_on_rank1()
    shutil.rmtree(work, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
