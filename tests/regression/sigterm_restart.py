#!/usr/bin/env python3
"""SIGTERM leaves a readable checkpoint from which the run resumes (foundation acceptance 4).

usage: sigterm_restart.py EXE WORKDIR
"""
import fcntl
import os
import shutil
import signal
import struct
import subprocess
import sys
import termios
import time

import h5py

from harness import MPI_ENV, Checks, run
import mote


def pending_bytes(fd):
    """Bytes written into the pipe and not yet read."""
    return struct.unpack("i", fcntl.ioctl(fd, termios.FIONREAD, b"\0\0\0\0"))[0]


exe, work = sys.argv[1], sys.argv[2]
deck = os.path.join(os.path.dirname(__file__), "..", "..", "problems", "gaussian_pulse", "gaussian_pulse.toml")
shutil.rmtree(work, ignore_errors=True)
out = os.path.join(work, "run")
args = [exe, deck, "grid.nx=128", "grid.ny=128", "run.t_end=1000", "run.progress_interval=0", f"output.dir={out}"]
proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=dict(os.environ, **MPI_ENV))
# Wait until the run is stepping, then stop reading until the pipe is full: the
# run is then blocked in a write of its log when SIGTERM comes (a user's
# `| tee` or a slow terminal), where the signal must not cost the rest of the
# log (a handler without SA_RESTART failed that write with EINTR, and
# std::cout dropped every later line).
lines = []
for line in proc.stdout:
    lines.append(line)
    if line.startswith("step") and len([l for l in lines if l.startswith("step")]) >= 20:
        break
fd = proc.stdout.fileno()
capacity = fcntl.fcntl(fd, fcntl.F_GETPIPE_SZ)
deadline = time.time() + 30
while pending_bytes(fd) < capacity - 1024 and time.time() < deadline:
    time.sleep(0.02)
full = pending_bytes(fd) >= capacity - 1024
time.sleep(0.1)
proc.send_signal(signal.SIGTERM)
rest, err = proc.communicate(timeout=120)
checks = Checks()
checks.check(full, f"the run's log filled the pipe ({capacity} bytes) before SIGTERM")
checks.check(proc.returncode == 4, f"exit code {proc.returncode} == 4 (interrupted, checkpoint written)")
checks.check("received SIGTERM" in rest, "the run reports the signal")
checks.check("  checkpoint " in rest.split("received SIGTERM")[-1], "and then logs the checkpoint it wrote")
latest = [f for f in os.listdir(out) if f.startswith("checkpoint_") and f.endswith(".h5")]
checks.check(len(latest) == 1, f"one checkpoint written ({latest})")
checks.check(not any(f.endswith(".tmp") for f in os.listdir(out)), "no temporary files left behind")
with h5py.File(os.path.join(out, latest[0])) as f:
    step = int(f.attrs["step"])
    checks.check(step > 0 and f["state/density"].shape == (128, 128), f"checkpoint readable at step {step}")
# Resume from it, with the deck stored in the checkpoint, for 10 more steps.
p = run([exe, "--restart", os.path.join(out, latest[0]), f"run.max_steps={step + 10}"])
checks.check(f"restarted from" in p.stdout, "restart from the checkpoint alone (stored deck)")
snap = mote.last_snapshot(out)
checks.check(snap.step == step + 10, f"resumed run reached step {snap.step} == {step + 10}")
sys.exit(checks.finish())
