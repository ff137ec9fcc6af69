#!/usr/bin/env python3
"""Exit code of a run on 2 ranks stopped by SIGTERM (issue 22, item 9).

    mpi_sigterm.py EXE WORKDIR LAUNCHER...

  * SIGTERM to the ranks (what srun and scancel do; kill on the rank processes): every rank
    writes its part of one checkpoint and exits 4, and mpirun returns 4;
  * SIGTERM to mpirun itself: Open MPI 4.1's mpirun forwards it to the ranks, kills them
    odls_base_sigkill_timeout seconds later (default 1, raised here to 5 so that the checkpoint
    is surely finished) and exits 1 whatever the ranks returned (docs/quickstart.md, "Exit codes"): the
    checkpoint is written and sound, the exit code is mpirun's 1.
A restart from each checkpoint on 2 ranks finishes. Ends with 'N passed, M failed'.
"""
import os
import re
import shutil
import signal
import subprocess
import sys

import h5py

from harness import MPI_ENV, Checks, run

INTERRUPTED = 4  # docs/quickstart.md, include/mote/core/exit_codes.hpp

exe, work, launcher = sys.argv[1], sys.argv[2], sys.argv[3:]
deck = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "problems", "gaussian_pulse",
                                    "gaussian_pulse.toml"))
checks = Checks()


def children(pid):
    """Pids of the processes whose parent is pid."""
    found = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat") as f:
                    if int(f.read().rsplit(")", 1)[1].split()[1]) == pid:
                        found.append(int(entry))
            except OSError:
                pass
    return found


def interrupted_run(name, signal_ranks):
    """Starts a long 2-rank run, sends SIGTERM to its ranks or to mpirun once it steps; returns (rc, output, dir).
    (mpirun drops the ranks' output after its own SIGTERM, so only the files can tell that case.)"""
    d = os.path.join(work, name)
    env = dict(os.environ, **MPI_ENV)
    if not signal_ranks:  # mpirun waits this long for every rank at the end, so not in the other case
        env["OMPI_MCA_odls_base_sigkill_timeout"] = "5"
    proc = subprocess.Popen([*launcher, exe, deck, "grid.nx=32", "grid.ny=32", "run.t_end=1000",
                             "run.progress_interval=0", f"output.dir={d}"], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, env=env)
    lines = []
    for line in proc.stdout:
        lines.append(line)
        if line.startswith("step") and sum(l.startswith("step") for l in lines) >= 20:
            break
    for pid in (children(proc.pid) if signal_ranks else [proc.pid]):
        os.kill(pid, signal.SIGTERM)
    rest = proc.communicate(timeout=120)[0]
    return proc.returncode, "".join(lines) + rest, d


def checkpoint_restarts(name, d):
    ckpts = sorted(f for f in os.listdir(d) if f.startswith("checkpoint_") and f.endswith(".h5"))
    checks.check(len(ckpts) == 1 and not any(f.endswith(".tmp") for f in os.listdir(d)),
                 f"{name}: one checkpoint, no temporary ({ckpts})")
    with h5py.File(os.path.join(d, ckpts[-1]), "r") as f:
        t_end = float(f.attrs["time"]) + 0.02  # a few steps past the checkpoint (dt about 0.0045)
    p = run([*launcher, exe, "--restart", "latest", deck, "grid.nx=32", "grid.ny=32", f"run.t_end={t_end!r}",
             f"output.dir={d}"], expect=None)
    steps = re.search(r"finished: (\d+) steps", p.stdout)
    checks.check(p.returncode == 0 and "restarted from" in p.stdout and steps and int(steps.group(1)) > 0,
                 f"{name}: the restart on 2 ranks steps on and finishes (exit {p.returncode}, "
                 f"{steps.group(1) if steps else 'no'} steps)")


def main():
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    rc, text, d = interrupted_run("ranks", signal_ranks=True)
    checks.check(rc == INTERRUPTED, f"SIGTERM to the ranks: mpirun exits {rc} == 4" + ("" if rc == 4 else text[-2000:]))
    checks.check("received SIGTERM" in text, "SIGTERM to the ranks: the run reports the signal")
    checkpoint_restarts("SIGTERM to the ranks", d)
    rc, text, d = interrupted_run("mpirun", signal_ranks=False)
    checks.check(rc == 1, f"SIGTERM to mpirun: mpirun exits {rc} == 1 (Open MPI's own code, documented)")
    checkpoint_restarts("SIGTERM to mpirun", d)
    shutil.rmtree(work, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
