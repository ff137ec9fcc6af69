#!/usr/bin/env python3
"""A checkpoint that one MPI rank alone cannot read is judged alike on every rank (issue 22).

    mpi_read_faults.py EXE WORKDIR LAUNCHER...

Runs gaussian_pulse (16 x 16) on 2 ranks; rank 1 runs without the capabilities that let root read any file
(setpriv --bounding-set -dac_override,-dac_read_search), and the newest checkpoint belongs to user nobody
with mode 0600: rank 0 can read it, rank 1 cannot. Every case must end within a time limit (no rank left
waiting for the other):
  * --restart latest skips the checkpoint on both ranks, naming rank 1 and the system error, and restarts
    from the previous one;
  * --restart FILE of it stops both ranks with exit 2 and one error line naming rank 1 and the system error,
    the files unchanged (checksums).
Skipped where this process is not root or setpriv is missing. Ends with 'N passed, M failed'.
"""
import os
import shutil
import sys

from harness import MPI_ENV, Checks, checksums, run_within

BAD_INPUT = 2  # docs/quickstart.md, include/mote/core/exit_codes.hpp
TIME_LIMIT = 60  # seconds; a run still going then has ranks waiting for each other
RANK1_OPTION = "--rank1-without-dac"
SETPRIV = "/usr/bin/setpriv"

if len(sys.argv) > 1 and sys.argv[1] == RANK1_OPTION:  # runs as a rank process
    cmd = sys.argv[2:]
    if os.environ.get("OMPI_COMM_WORLD_RANK") == "1":
        cmd = [SETPRIV, "--bounding-set", "-dac_override,-dac_read_search", *cmd]
    os.execv(cmd[0], cmd)

exe, work, launcher = sys.argv[1], sys.argv[2], sys.argv[3:]
deck = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "problems", "gaussian_pulse",
                                    "gaussian_pulse.toml"))
common = [deck, "grid.nx=16", "grid.ny=16", "output.checkpoint_every=4", "output.checkpoints_kept=10",
          "run.progress_interval=0"]
ENV = dict(os.environ, **MPI_ENV, PMIX_MCA_gds="hash", OMPI_MCA_btl="self,tcp")
checks = Checks()


def mpirun(args):
    return run_within([*launcher, sys.executable, os.path.abspath(__file__), RANK1_OPTION, exe, *args], TIME_LIMIT,
                      env=ENV, cwd=work)


def run_with_unreadable_newest(name):
    """A 2-rank run of 8 steps into WORKDIR/name whose newest checkpoint rank 1 cannot read; returns
    (directory, older checkpoints, the unreadable one)."""
    d = os.path.join(work, name)
    rc, text = mpirun([*common, f"output.dir={d}", "run.max_steps=8"])
    if rc != 0:
        raise AssertionError(f"the first part of {name} exited {rc}\n{text[-3000:]}")
    ckpts = sorted(f for f in os.listdir(d) if f.startswith("checkpoint_"))
    newest = os.path.join(d, ckpts[-1])
    os.chown(newest, 65534, 65534)  # nobody
    os.chmod(newest, 0o600)
    return d, ckpts[:-1], newest


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
    if os.geteuid() != 0 or not os.path.exists(SETPRIV):
        print("SKIP: needs root and setpriv to make a file unreadable for one rank alone")
        return 0
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    restart_latest()
    restart_file()
    shutil.rmtree(work, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
