#!/usr/bin/env python3
"""An output directory belongs to one run; restarts continue only their own run (issue 22, items 1-2).

    run_directories.py EXE NO_FLOCK_LIBRARY WORKDIR

Runs gaussian_pulse (16 x 16) and checks, each with the exit code, the message
and checksums of the files that must not change:
  * a run stores one run id in run_id, every snapshot, every checkpoint and the history header,
    and removes its lock file run.lock at exit (also after SIGTERM); the file a run killed by SIGKILL
    leaves is taken over by the next run;
  * a second run into a directory locked by a live process (a running run, or this script holding
    the flock of run.lock) is refused with exit 2 before anything is written; a lock file that no
    process holds (left by a killed run; naming a dead pid, or this live script) is taken over with
    a warning;
  * where flock fails (NO_FLOCK_LIBRARY under LD_PRELOAD, as on a file system without locks), the
    lock file's existence locks: one naming a live process refuses, a dead pid of this host is
    taken over, and a run removes its own;
  * a new run into a directory holding a run's files is refused (exit 2); output.overwrite=true
    replaces them with a new run id;
  * --restart latest refuses a checkpoint of another run copied into the directory (exit 2);
  * --restart FILE without a deck writes beside the checkpoint, not into the stored relative
    output.dir, leaving the original run's files unchanged; the stored run.max_steps does not
    carry over, one given on the command line does.
Ends with 'N passed, M failed'.
"""
import fcntl
import os
import shutil
import signal
import socket
import subprocess
import sys

import h5py

from harness import MPI_ENV, Checks, checksums, run
import mote

BAD_INPUT, INTERRUPTED = 2, 4  # docs/quickstart.md, include/mote/core/exit_codes.hpp

exe, no_flock, work = sys.argv[1], sys.argv[2], sys.argv[3]
deck = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "problems", "gaussian_pulse",
                                    "gaussian_pulse.toml"))
common = ["grid.nx=16", "grid.ny=16", "output.checkpoint_every=4", "output.checkpoints_kept=10",
          "run.progress_interval=0"]
checks = Checks()


def case(name, cmd, code, expected, unchanged=(), cwd=None, env=None):
    """Runs cmd; checks its exit code, that its output holds every `expected` text and that the
    directories in `unchanged` hold the same files with the same bytes afterwards."""
    before = {d: checksums(d) for d in unchanged}
    p = run(cmd, expect=None, cwd=cwd or work, extra_env=env)
    text = p.stdout + p.stderr
    checks.check(p.returncode == code, f"{name}: exit code {p.returncode} == {code}" +
                 ("" if p.returncode == code else f"\n{text[-2000:]}"))
    for e in expected:
        checks.check(e in text, f"{name}: message contains {e!r}" + ("" if e in text else f"\n{text[-2000:]}"))
    for d in unchanged:
        checks.check(checksums(d) == before[d], f"{name}: files of {os.path.basename(d)} unchanged")
    return text


def run_id(directory):
    with open(os.path.join(directory, "run_id")) as f:
        return f.read().strip()


def latest_checkpoint(directory):
    return sorted(f for f in os.listdir(directory) if f.startswith("checkpoint_") and f.endswith(".h5"))[-1]


def write_lock(directory, pid):
    os.makedirs(directory, exist_ok=True)
    with open(os.path.join(directory, "run.lock"), "w") as f:
        f.write(f"host {socket.gethostname()}\npid {pid}\nstarted 2026-01-01T00:00:00Z\n")


def dead_pid():
    p = subprocess.Popen(["true"])
    p.wait()
    return p.pid


def run_ids_everywhere(a):
    """Run a: one run id in run_id, every snapshot and checkpoint and the history header; no lock left."""
    rid = run_id(a)
    checks.check(len(rid) == 16 and all(c in "0123456789abcdef" for c in rid), f"run_id holds a 64-bit id ({rid})")
    stored = set()
    for name in os.listdir(a):
        if name.endswith(".h5"):
            with h5py.File(os.path.join(a, name)) as f:
                stored.add(f.attrs["run_id"].decode())
    checks.check(stored == {rid}, f"every snapshot and checkpoint stores run id {rid} ({stored})")
    with open(os.path.join(a, "history.txt")) as f:
        checks.check(f.readlines()[1] == f"# run_id {rid}\n", "history header holds the run id")
    checks.check(not os.path.exists(os.path.join(a, "run.lock")), "no lock file left after the run")


def two_runs_at_once():
    """A run in progress holds its lock: a second run into its directory is refused; SIGTERM releases it;
    after SIGKILL (no clean-up; as MPI_Abort from another rank ends rank 0) the next run takes it over."""
    busy = os.path.join(work, "busy")
    args = [exe, deck, *common, "grid.nx=64", "grid.ny=64", "run.t_end=1000", "output.checkpoint_every=0", "run.progress_interval=1",
            f"output.dir={busy}"]
    proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            env=dict(os.environ, **MPI_ENV))
    for line in proc.stdout:
        if line.startswith("step"):
            break
    case("second run while one runs", [exe, deck, *common, f"output.dir={busy}", "output.overwrite=true"],
         BAD_INPUT, [f"output directory '{busy}' is in use by another run", f"pid {proc.pid} on host"])
    proc.send_signal(signal.SIGTERM)
    proc.communicate(timeout=120)
    checks.check(proc.returncode == INTERRUPTED, f"the first run ends by SIGTERM (exit {proc.returncode})")
    checks.check(not os.path.exists(os.path.join(busy, "run.lock")), "SIGTERM: the lock file is removed")
    proc = subprocess.Popen([*args, "output.overwrite=true"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True, env=dict(os.environ, **MPI_ENV))
    for line in proc.stdout:
        if line.startswith("step"):
            break
    proc.kill()
    proc.communicate(timeout=120)
    checks.check(os.path.exists(os.path.join(busy, "run.lock")), "SIGKILL: the lock file is left behind")
    case("a run after one killed by SIGKILL", [exe, deck, *common, f"output.dir={busy}", "output.overwrite=true"], 0,
         [f"taking over the lock file '{busy}/run.lock' of pid {proc.pid} on host",
          "that run has ended without removing it", "finished"])


def locks(a):
    """A lock file whose flock a live process (this script) holds refuses; one that no process holds is
    taken over, whether it names a dead process or a live one (another host's run, a reused pid)."""
    write_lock(a, os.getpid())
    with open(os.path.join(a, "run.lock")) as held:
        fcntl.flock(held, fcntl.LOCK_EX)
        case("restart into a locked directory", [exe, "--restart", "latest", deck, *common, f"output.dir={a}"],
             BAD_INPUT, [f"output directory '{a}' is in use by another run: lock file '{a}/run.lock' is held by "
                         f"pid {os.getpid()} on host {socket.gethostname()}"], unchanged=[a])
    fresh = os.path.join(work, "locked_empty")
    write_lock(fresh, os.getpid())
    with open(os.path.join(fresh, "run.lock")) as held:
        fcntl.flock(held, fcntl.LOCK_EX)
        case("new run into a locked empty directory", [exe, deck, *common, f"output.dir={fresh}"], BAD_INPUT,
             ["is in use by another run"], unchanged=[fresh])
    checks.check(os.listdir(fresh) == ["run.lock"], "nothing written beside the lock")
    os.remove(os.path.join(a, "run.lock"))
    pid = dead_pid()
    for owner in (pid, os.getpid()):
        shutil.rmtree(fresh)
        write_lock(fresh, owner)
        case(f"lock file left by pid {owner}, held by none", [exe, deck, *common, f"output.dir={fresh}"], 0,
             [f"taking over the lock file '{fresh}/run.lock' of pid {owner}", "that run has ended without removing it"])
        checks.check(not os.path.exists(os.path.join(fresh, "run.lock")), "taken-over lock: removed at exit")


def locks_without_flock():
    """Where flock fails, the lock file's existence locks (a dead pid of this host is taken over)."""
    env = {"LD_PRELOAD": no_flock}
    d = os.path.join(work, "no_flock")
    write_lock(d, os.getpid())
    case("no flock: lock naming a live process", [exe, deck, *common, f"output.dir={d}"], BAD_INPUT,
         ["does not support flock", f"is in use by another run: lock file '{d}/run.lock' is held by pid {os.getpid()}"],
         unchanged=[d], env=env)
    pid = dead_pid()
    write_lock(d, pid)
    case("no flock: stale lock", [exe, deck, *common, f"output.dir={d}"], 0,
         ["does not support flock", f"taking over the stale lock file '{d}/run.lock' of pid {pid}",
          "that process no longer exists", "finished"], env=env)
    checks.check(not os.path.exists(os.path.join(d, "run.lock")), "no flock: the run removes its lock at exit")
    case("no flock: a run into a directory without a lock", [exe, deck, *common, f"output.dir={d}",
                                                             "output.overwrite=true"], 0, ["finished"], env=env)
    checks.check(not os.path.exists(os.path.join(d, "run.lock")), "no flock: lock removed at exit")


def used_directory(a):
    """A new run into a run's directory is refused; output.overwrite=true replaces that run."""
    case("new run into a used directory", [exe, deck, *common, f"output.dir={a}"], BAD_INPUT,
         [f"output directory '{a}' holds the files of an earlier run", "output.overwrite = true"], unchanged=[a])
    old = run_id(a)
    stray = os.path.join(a, "checkpoint_00099.h5")
    shutil.copy(os.path.join(a, latest_checkpoint(a)), stray)
    case("output.overwrite=true", [exe, deck, *common, f"output.dir={a}", "output.overwrite=true"], 0,
         ["deleted", "files of the earlier run"])
    checks.check(run_id(a) != old and not os.path.exists(stray), "overwrite: a new run id, the earlier files gone")


def foreign_checkpoint(a):
    """--restart latest refuses a checkpoint of another run that was copied into the directory."""
    b = os.path.join(work, "other")
    run([exe, deck, *common, f"output.dir={b}"], cwd=work)
    foreign = os.path.join(a, "checkpoint_00099.h5")
    shutil.copy(os.path.join(b, latest_checkpoint(b)), foreign)
    case("restart latest, foreign checkpoint", [exe, "--restart", "latest", deck, *common, f"output.dir={a}"],
         BAD_INPUT, [f"checkpoint '{foreign}' belongs to run {run_id(b)}, not to run {run_id(a)} that owns output "
                     f"directory '{a}'"], unchanged=[a, b])
    os.remove(foreign)


def restart_from_file():
    """--restart FILE without a deck: beside the file, not into the stored relative output.dir; max_steps."""
    case("first part (max_steps=5)", [exe, deck, *common, "output.dir=orig", "run.max_steps=5"], 0,
         ["stopped at run.max_steps"])
    orig = os.path.join(work, "orig")
    branch, limited = os.path.join(work, "branch"), os.path.join(work, "limited")
    for d in (branch, limited):
        os.makedirs(d)
        shutil.copy(os.path.join(orig, latest_checkpoint(orig)), d)
    text = case("restart FILE, no deck", [exe, "--restart", os.path.join("branch", latest_checkpoint(branch))], 0,
                ["restarted from", "finished"], unchanged=[orig])
    checks.check(mote.last_snapshot(branch).time == 0.4, "the branch ran to run.t_end (max_steps not carried over)")
    checks.check(os.path.exists(os.path.join(branch, "history.txt")) and run_id(branch) == run_id(orig),
                 "the branch writes beside its checkpoint, continuing the checkpoint's run")
    checks.check(f"dir = \"{branch}\"" in text, "the resolved deck names the checkpoint's directory")
    case("restart FILE, run.max_steps=8", [exe, "--restart", os.path.join(limited, latest_checkpoint(limited)),
                                           "run.max_steps=8"], 0, ["stopped at run.max_steps"], unchanged=[orig])
    checks.check(mote.last_snapshot(limited).step == 8, "a max_steps given again on the command line applies")


def main():
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    a = os.path.join(work, "a")
    case("first run", [exe, deck, *common, f"output.dir={a}"], 0, ["finished"])
    run_ids_everywhere(a)
    two_runs_at_once()
    locks(a)
    locks_without_flock()
    used_directory(a)
    foreign_checkpoint(a)
    restart_from_file()
    shutil.rmtree(work, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
