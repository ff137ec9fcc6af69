#!/usr/bin/env python3
"""SIGTERM leaves a readable checkpoint from which the run resumes (foundation acceptance 4),
also when the log goes to a pipe whose reader has stopped or died.

usage: sigterm_restart.py EXE WORKDIR

1. The run logs to a pipe that this script stops reading once the run is stepping:
   SIGTERM comes while the run is blocked in a write of its log. The checkpoint must
   appear while the reader is still stopped (a paused pager, Ctrl-S); once the pipe is
   read again, the rest of the log (the signal, the checkpoint) must follow it.
2. The run's reader dies (a `| tee` killed with the job) and then SIGTERM comes: the
   run must not die of SIGPIPE, but write its checkpoint and exit with code 4.
3. The checkpoint of 1 resumes the run with the deck stored in it.
"""
import fcntl
import os
import shutil
import signal
import struct
import subprocess
import sys
import termios
import threading
import time

import h5py

from harness import MPI_ENV, Checks, run
import mote

exe, work = sys.argv[1], sys.argv[2]
deck = os.path.join(os.path.dirname(__file__), "..", "..", "problems", "gaussian_pulse", "gaussian_pulse.toml")
shutil.rmtree(work, ignore_errors=True)
checks = Checks()


def pending_bytes(fd):
    """Bytes written into the pipe and not yet read."""
    return struct.unpack("i", fcntl.ioctl(fd, termios.FIONREAD, b"\0\0\0\0"))[0]


def start(out, stderr, timeout=120.0):
    args = [exe, deck, "grid.nx=128", "grid.ny=128", "run.t_end=1000", "run.progress_interval=0", f"output.dir={out}"]
    proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=stderr, text=True, env=dict(os.environ, **MPI_ENV))
    watchdog = threading.Timer(timeout, proc.kill)  # a run that hangs before stepping ends the read below
    watchdog.start()
    steps = 0
    try:
        for line in proc.stdout:  # until the run is stepping
            steps += line.startswith("step")
            if steps >= 20:
                break
    finally:
        watchdog.cancel()
    if steps < 20:
        proc.kill()
        checks.check(False, f"the run printed {steps} of 20 step lines within {timeout:.0f} s")
        sys.exit(checks.finish())
    return proc


def wait_for_blocked_writer(fd, timeout=60.0):
    """True once the pipe holds unread bytes that stop growing (the writer is blocked)."""
    deadline, last, since = time.time() + timeout, -1, time.time()
    while time.time() < deadline:
        now = pending_bytes(fd)
        if now != last:
            last, since = now, time.time()
        elif now > 0 and time.time() - since > 0.5:
            return True
        time.sleep(0.05)
    return False


def checkpoints(out):
    return [f for f in os.listdir(out) if f.startswith("checkpoint_") and f.endswith(".h5")]


# 1. A stopped reader.
out = os.path.join(work, "run")
proc = start(out, subprocess.DEVNULL)
blocked = wait_for_blocked_writer(proc.stdout.fileno())
checks.check(blocked, "the run's log filled the pipe and the run blocked in a write")
proc.send_signal(signal.SIGTERM)
deadline = time.time() + 60
while not checkpoints(out) and time.time() < deadline:
    time.sleep(0.1)
checks.check(len(checkpoints(out)) == 1, f"the checkpoint is written while the reader is stopped ({checkpoints(out)})")
rest, _ = proc.communicate(timeout=120)
checks.check(proc.returncode == 4, f"exit code {proc.returncode} == 4 (interrupted, checkpoint written)")
after = rest.split("  checkpoint ")[-1]
checks.check("  checkpoint " in rest and "received SIGTERM" in after,
             "the log goes on after the pipe is read again: the checkpoint, then the signal")
latest = checkpoints(out)
checks.check(not any(f.endswith(".tmp") for f in os.listdir(out)), "no temporary files left behind")
with h5py.File(os.path.join(out, latest[0])) as f:
    step = int(f.attrs["step"])
    checks.check(step > 0 and f["state/density"].shape == (128, 128), f"checkpoint readable at step {step}")

# 2. A dead reader.
dead = os.path.join(work, "dead_reader")
proc = start(dead, subprocess.DEVNULL)
proc.stdout.close()
time.sleep(0.2)
proc.send_signal(signal.SIGTERM)
code = proc.wait(timeout=120)
checks.check(code == 4, f"reader gone: exit code {code} == 4, not killed by SIGPIPE ({-signal.SIGPIPE})")
checks.check(len(checkpoints(dead)) == 1, f"reader gone: the checkpoint is written ({checkpoints(dead)})")

# 3. Resume from the checkpoint of 1, with the deck stored in it, for 10 more steps.
p = run([exe, "--restart", os.path.join(out, latest[0]), f"run.max_steps={step + 10}"])
checks.check("restarted from" in p.stdout, "restart from the checkpoint alone (stored deck)")
snap = mote.last_snapshot(out)
checks.check(snap.step == step + 10, f"resumed run reached step {snap.step} == {step + 10}")
sys.exit(checks.finish())
