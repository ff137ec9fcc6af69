#!/usr/bin/env python3
"""Runs that cannot lose or mix data: full disks, damaged checkpoints, changed decks (issue 22, items 3, 5-7).

    fault_matrix.py EXE WORKDIR

Runs gaussian_pulse (16 x 16) and checks, each with the exit code, the message
and checksums of the files that must not change:
  * full disk during a snapshot (RLIMIT_FSIZE between the sizes of a checkpoint and a
    snapshot): exit 5 naming the file and "File too large", a checkpoint of the state
    written before stopping, no .tmp, no HDF5 error stack in the output, no "infinite loop
    closing library", earlier files unchanged;
  * the same with a limit below a checkpoint: no checkpoint either, the earlier ones kept
    and restartable;
  * history.txt on a full disk (RLIMIT) and on /dev/full, the XDMF on /dev/full: exit 5 naming
    the file and the system error; the history keeps only complete rows;
  * the restart from the checkpoint written after a failed snapshot or history row writes that
    output first: every scheduled snapshot once, numbered in time order; a history row per step;
  * a restart from a checkpoint older than the newest sets the later checkpoints and snapshots
    aside (superseded_NNNNN/), so that --restart latest continues it, and ends as the first run;
  * a small tmpfs filling up (only where this process may mount one, else skipped);
  * truncated, bit-flipped (in a state dataset, in the time attribute and in the stored deck)
    and NaN-holding checkpoints: --restart FILE refuses them (exit 2, naming the defect),
    --restart latest skips them with a warning naming each and restarts from the previous
    sound one; one of another problem (disc_pulse) is refused naming both problems;
  * a restart whose deck changes physics or geometry (transport.vx, grid.x_max) is refused
    (exit 2) naming the key and both values; restart-mutable keys (run.t_end) may change;
    --force accepts a change and logs it; a resolution change (grid.nx) is refused with and
    without --force, naming the key and both values, not a dataset shape.
Ends with 'N passed, M failed'.
"""
import os
import resource
import shutil
import signal
import struct
import subprocess
import sys
import time

import h5py
import numpy as np

from harness import Checks, checksums, files, hdf5_datasets, run, unreadable_hdf5

BAD_INPUT, IO_ERROR = 2, 5  # docs/quickstart.md, include/mote/core/exit_codes.hpp

exe, work = sys.argv[1], sys.argv[2]
deck = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "problems", "gaussian_pulse",
                                    "gaussian_pulse.toml"))
common = ["grid.nx=16", "grid.ny=16", "output.checkpoint_every=4", "output.checkpoints_kept=10",
          "run.progress_interval=0"]
checks = Checks()
# Open MPI's singleton start-up keeps PMIx data in shared-memory files, which RLIMIT_FSIZE would break.
os.environ["PMIX_MCA_gds"] = "hash"


def file_size_limit(limit):
    """preexec_fn: writes beyond `limit` bytes per file fail with EFBIG (SIGXFSZ ignored)."""
    def apply():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    return apply


def case(name, cmd, code, expected, absent=(), unchanged=None, skip=(), limit=None):
    """Runs cmd (under a file-size limit if given); checks the exit code, that the output holds every
    `expected` and no `absent` text, and that the files of directory `unchanged` (but `skip`) keep their bytes."""
    before = checksums(unchanged, skip) if unchanged else None
    start = time.time()
    p = run(cmd, expect=None, cwd=work, preexec_fn=file_size_limit(limit) if limit else None)
    text = p.stdout + p.stderr
    checks.check(p.returncode == code, f"{name}: exit code {p.returncode} == {code} ({time.time() - start:.1f} s)" +
                 ("" if p.returncode == code else f"\n{text[-3000:]}"))
    for e in expected:
        checks.check(e in text, f"{name}: message contains {e!r}" + ("" if e in text else f"\n{text[-3000:]}"))
    for e in absent:
        checks.check(e not in text, f"{name}: output does not contain {e!r}" + ("" if e not in text else
                                                                              f"\n{text[-3000:]}"))
    if unchanged:
        after = checksums(unchanged, skip)
        kept = {n: s for n, s in after.items() if n in before}
        checks.check(kept == before and set(before) <= set(after), f"{name}: earlier files unchanged")
    return text


def fresh_run(name, *extra):
    """A run of 6 steps (checkpoints at steps 4 and 6) into WORKDIR/name; returns the directory."""
    d = os.path.join(work, name)
    run([exe, deck, *common, f"output.dir={d}", "run.max_steps=6", *extra], cwd=work)
    return d


def no_temporaries(name, d):
    tmp = [f for f in os.listdir(d) if f.endswith(".tmp")]
    checks.check(not tmp, f"{name}: no temporary file left ({tmp})")


def history_rows_complete(name, d):
    """Every row of history.txt has as many columns as its header."""
    with open(os.path.join(d, "history.txt")) as f:
        text = f.read()
    lines = text.splitlines()
    columns = len(lines[0].split()) - 1
    rows = [l for l in lines if not l.startswith("#")]
    ok = text.endswith("\n") and all(len(r.split()) == columns for r in rows)
    checks.check(ok, f"{name}: history.txt holds only complete rows ({len(rows)})")


HDF5_NOISE = ["HDF5-DIAG", "infinite loop closing library", "#000:"]


def full_disk_snapshot():
    """RLIMIT between a checkpoint's and a snapshot's size: the snapshot fails, the checkpoint is written."""
    d = fresh_run("disk_snapshot")
    ckpt = os.path.getsize(os.path.join(d, files(d, "checkpoint_")[-1]))
    snap = os.path.getsize(os.path.join(d, files(d, "snapshot_")[-1]))
    checks.check(snap > ckpt + 2000, f"a snapshot ({snap} B) is larger than a checkpoint ({ckpt} B)")
    before, next_snapshot = files(d, "checkpoint_"), f"snapshot_{len(files(d, 'snapshot_')):05d}.h5"
    case("full disk during a snapshot", [exe, "--restart", "latest", deck, *common, f"output.dir={d}",
                                         "output.checkpoint_every=0"], IO_ERROR,
         [f"cannot write '{d}/{next_snapshot}.tmp': File too large", "writing a checkpoint before stopping"], HDF5_NOISE, unchanged=d, skip=("history.txt",),
         limit=(ckpt + snap) // 2)
    no_temporaries("full disk during a snapshot", d)
    checks.check(not os.path.exists(os.path.join(d, next_snapshot)), "no snapshot under its final name")
    new = [f for f in files(d, "checkpoint_") if f not in before]
    checks.check(len(new) == 1, f"a checkpoint of the state was written before stopping ({new})")
    history_rows_complete("full disk during a snapshot", d)
    case("restart from that checkpoint", [exe, "--restart", "latest", deck, *common, f"output.dir={d}"], 0,
         [f"restarted from {os.path.join(d, new[0]) if new else '?'}", "that a failed write left out", "finished"])
    with h5py.File(os.path.join(d, new[0])) as f:
        t_failed = f.attrs["time"]
    checks.check(os.path.exists(os.path.join(d, next_snapshot)) and snapshot_time(d, next_snapshot) == t_failed,
                 f"the restart wrote the snapshot the full disk left out ({next_snapshot}, t = {t_failed})")
    schedule_complete("full disk during a snapshot", d)


def snapshot_time(d, name):
    with h5py.File(os.path.join(d, name)) as f:
        return float(f.attrs["time"])


def schedule_complete(name, d):
    """Snapshots numbered without a gap, in increasing time, one at every scheduled time k 0.1 to t_end = 0.4."""
    names = files(d, "snapshot_")
    times = [snapshot_time(d, n) for n in names]
    numbered = names == [f"snapshot_{k:05d}.h5" for k in range(len(names))]
    scheduled = all(any(abs(t - 0.1 * k) <= 1e-12 for t in times) for k in range(5))
    checks.check(numbered and times == sorted(set(times)) and scheduled,
                 f"{name}: every scheduled snapshot written once, numbered in time order ({len(names)}: {times})")


def full_disk_everything():
    """RLIMIT below a checkpoint's size: snapshot and checkpoint fail; the earlier checkpoints remain."""
    d = fresh_run("disk_full")
    ckpt = os.path.getsize(os.path.join(d, files(d, "checkpoint_")[-1]))
    case("full disk, no checkpoint fits", [exe, "--restart", "latest", deck, *common, f"output.dir={d}",
                                           "output.checkpoint_every=0"], IO_ERROR,
         ["File too large", "the checkpoint could not be written either",
          f"the last checkpoint is {os.path.join(d, files(d, 'checkpoint_')[-1])}"], HDF5_NOISE,
         unchanged=d, skip=("history.txt",), limit=ckpt - 1000)
    no_temporaries("full disk, no checkpoint fits", d)
    case("restart after the full disk", [exe, "--restart", "latest", deck, *common, f"output.dir={d}"], 0,
         ["finished"])


def full_disk_history():
    """history.txt reaching RLIMIT (no snapshot due before the end): exit 5, only complete rows kept."""
    d = fresh_run("disk_history")
    size = os.path.getsize(os.path.join(d, "history.txt"))
    case("full disk in the history", [exe, "--restart", "latest", deck, *common, f"output.dir={d}",
                                      "output.snapshot_dt=0", "output.checkpoint_every=0"], IO_ERROR,
         [f"cannot write history file '{d}/history.txt': File too large"], HDF5_NOISE[:2], unchanged=d,
         skip=("history.txt",), limit=size + 250)
    history_rows_complete("full disk in the history", d)
    no_temporaries("full disk in the history", d)

    # A limit above a checkpoint's size: the history row is lost, the checkpoint written before stopping
    # records it, and the restart writes it before its first step.
    d = fresh_run("disk_history_row")
    ckpt = os.path.getsize(os.path.join(d, files(d, "checkpoint_")[-1]))
    longer = ["run.t_end=1.2", "output.snapshot_dt=0", "output.checkpoint_every=0"]
    case("full disk in the history, a checkpoint fits", [exe, "--restart", "latest", deck, *common,
                                                         f"output.dir={d}", *longer], IO_ERROR,
         ["File too large", "writing a checkpoint before stopping"], HDF5_NOISE[:2], limit=ckpt + 1500)
    case("restart after the lost history row", [exe, "--restart", "latest", deck, *common, f"output.dir={d}",
                                                *longer], 0, ["that a failed write left out", "finished"])
    with open(os.path.join(d, "history.txt")) as f:
        steps = [int(l.split()[0]) for l in f if not l.startswith("#")]
    checks.check(steps == list(range(steps[-1] + 1)) and steps[-1] > 80,
                 f"restart after the lost history row: a row for every step 0-{steps[-1]}, the lost one written")


def dev_full():
    """The history's, an XDMF file's and snapshots.xmf's temporaries on /dev/full: exit 5 with ENOSPC, nothing
    half-written."""
    d = fresh_run("dev_full")
    os.symlink("/dev/full", os.path.join(d, "history.txt.tmp"))
    case("history on /dev/full", [exe, "--restart", "latest", deck, *common, f"output.dir={d}"], IO_ERROR,
         [f"cannot write '{d}/history.txt.tmp': No space left on device"], unchanged=d)
    checks.check(not os.path.lexists(os.path.join(d, "history.txt.tmp")), "history on /dev/full: temporary removed")
    before, xmf = files(d, "checkpoint_"), f"snapshot_{len(files(d, 'snapshot_')):05d}.xmf"
    os.symlink("/dev/full", os.path.join(d, xmf + ".tmp"))
    case("XDMF on /dev/full", [exe, "--restart", "latest", deck, *common, f"output.dir={d}",
                               "output.checkpoint_every=0"], IO_ERROR,
         [f"cannot write '{d}/{xmf}.tmp': No space left on device", "writing a checkpoint"],
         unchanged=d, skip=("history.txt",))
    checks.check(not os.path.exists(os.path.join(d, xmf)), "XDMF on /dev/full: no .xmf file")
    checks.check(len(files(d, "checkpoint_")) == len(before) + 1, "XDMF on /dev/full: a checkpoint was written")
    d = fresh_run("dev_full_series")
    series = os.path.join(d, "snapshots.xmf")
    with open(series, "rb") as f:
        old = f.read()
    before = files(d, "checkpoint_")
    os.symlink("/dev/full", series + ".tmp")
    case("time series on /dev/full", [exe, "--restart", "latest", deck, *common, f"output.dir={d}",
                                      "output.checkpoint_every=0"], IO_ERROR,
         [f"cannot write '{series}.tmp': No space left on device", "writing a checkpoint"])
    with open(series, "rb") as f:
        checks.check(f.read() == old, "time series on /dev/full: snapshots.xmf keeps its bytes")
    checks.check(not os.path.lexists(series + ".tmp"), "time series on /dev/full: temporary removed")
    checks.check(len(files(d, "checkpoint_")) == len(before) + 1, "time series on /dev/full: a checkpoint was written")


def small_tmpfs():
    """A 192 KiB tmpfs filling up during a run: exit 5, no .tmp, every .h5 left readable."""
    d = os.path.join(work, "tmpfs")
    os.makedirs(d)
    if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=192k", "tmpfs", d], capture_output=True).returncode != 0:
        print("SKIP small tmpfs: cannot mount one here (needs root); the RLIMIT and /dev/full cases cover full disks")
        return
    try:
        case("tmpfs full", [exe, deck, *common, f"output.dir={d}", "grid.nx=48", "grid.ny=48",
                            "output.checkpoint_every=2"], IO_ERROR, ["No space left on device"], HDF5_NOISE)
        no_temporaries("tmpfs full", d)
        bad = unreadable_hdf5(d)
        checks.check(not bad, f"tmpfs full: every .h5 under a final name is readable ({bad})")
    finally:
        subprocess.run(["umount", d])


def flip_bit_of(path, pattern):
    """Flips the lowest bit of the first byte of the first occurrence of `pattern` in the file at path."""
    with open(path, "rb") as f:
        data = f.read()
    offset = data.index(pattern)
    with open(path, "r+b") as f:
        f.seek(offset)
        f.write(bytes([data[offset] ^ 1]))


def damage(d):
    """Damaged copies of the newest checkpoint of d (truncated, one bit flipped in a dataset, in the time (an
    attribute: /@time or /state@tau) and in the stored deck (/@deck), a NaN); returns them."""
    newest = os.path.join(d, files(d, "checkpoint_")[-1])
    with h5py.File(newest, "r") as f:
        time = float(f.attrs["time"])
    out = {}
    for kind in ("truncated", "bitflip", "attribute_time", "attribute_deck", "nan"):
        path = os.path.join(work, f"{kind}.h5")
        shutil.copy(newest, path)
        out[kind] = path
    with open(out["truncated"], "r+b") as f:
        f.truncate(os.path.getsize(newest) // 2)
    with h5py.File(out["bitflip"], "r") as f:
        offset = f["/state/density"].id.get_offset()
    with open(out["bitflip"], "r+b") as f:
        f.seek(offset + 8 * 37)
        byte = f.read(1)[0]
        f.seek(offset + 8 * 37)
        f.write(bytes([byte ^ 1]))
    flip_bit_of(out["attribute_time"], struct.pack("<d", time))
    flip_bit_of(out["attribute_deck"], b"diffusivity = 0.01")
    with h5py.File(out["nan"], "r+") as f:
        f["/state/density"][3, 5] = np.nan
    return out


def disc_pulse_checkpoint():
    """A sound checkpoint of another problem (disc_pulse, one step)."""
    d = os.path.join(work, "disc_pulse")
    disc = os.path.join(os.path.dirname(exe), "disc_pulse")
    run([disc, os.path.join(os.path.dirname(deck), "..", "disc_pulse", "disc_pulse.toml"), "grid.nr=16",
         "grid.ntheta=16", "run.max_steps=1", f"output.dir={d}"], cwd=work)
    return os.path.join(d, files(d, "checkpoint_")[-1])


def damaged_checkpoints():
    """--restart FILE refuses a damaged checkpoint; --restart latest skips it for the previous sound one."""
    d = fresh_run("damaged")
    ckpts = files(d, "checkpoint_")
    bad = damage(d)
    attributes = "its attributes (time, step, run id, deck, ...) do not match their checksum"
    expected = {"truncated": "it cannot be read", "bitflip": "dataset /state/density does not match its checksum",
                "attribute_time": attributes, "attribute_deck": attributes,
                "nan": "dataset /state/density holds a non-finite value"}
    for kind, path in bad.items():
        case(f"restart FILE {kind}", [exe, "--restart", path, deck, *common, f"output.dir={d}"], BAD_INPUT,
             [f"cannot restart from checkpoint '{path}': {expected[kind]}"], unchanged=d)
    newest, previous = os.path.join(d, ckpts[-1]), os.path.join(d, ckpts[-2])
    for kind, path in bad.items():
        shutil.copy(path, newest)
        case(f"restart latest, newest {kind}", [exe, "--restart", "latest", deck, *common, f"output.dir={d}",
                                                "run.max_steps=6"], 0,
             [f"skipping checkpoint '{newest}': {expected[kind]}", f"restarted from {previous} at step 4"])
    foreign = disc_pulse_checkpoint()
    case("restart FILE of another problem", [exe, "--restart", foreign, deck, *common, f"output.dir={d}"], BAD_INPUT,
         [f"checkpoint '{foreign}' belongs to problem 'disc_pulse', not 'gaussian_pulse'"], unchanged=d)
    for c in ckpts:
        shutil.copy(bad["bitflip"], os.path.join(d, c))
    case("restart latest, all damaged", [exe, "--restart", "latest", deck, *common, f"output.dir={d}"], BAD_INPUT,
         [f"none of the {len(ckpts)} checkpoints in '{d}' is sound"], unchanged=d)


def changed_decks():
    """A restart may change restart-mutable keys only, unless forced; a resolution change is named as such."""
    d = fresh_run("decks")
    restart = [exe, "--restart", "latest", deck, *common, f"output.dir={d}"]
    for key, new, old in (("transport.vx", "2.0", "1.0"), ("grid.x_max", "2.0", "1.0")):
        case(f"restart with {key} changed", [*restart, f"{key}={new}"], BAD_INPUT,
             ["in keys that may not change on restart (--force to accept)",
              f"{key} = {old} in the checkpoint, {new} now"], ["shape"], unchanged=d)
    for force in ([], ["--force"]):
        case(f"restart with grid.nx changed {' '.join(force)}", [*restart, "grid.nx=32", *force], BAD_INPUT,
             ["the deck changes the size of the state stored in checkpoint", "which no restart can change, not even "
              "with --force", "grid.nx = 16 in the checkpoint, 32 now"], ["shape", "HDF5"], unchanged=d)
    case("restart with run.t_end changed", [*restart, "run.t_end=0.3", "run.max_steps=8"], 0,
         ["restart changes run.t_end = 0.4 in the checkpoint, 0.3 now", "stopped at run.max_steps"])
    case("--force", [*restart, "transport.vx=2.0", "--force"], 0,
         ["--force: restart changes transport.vx = 1.0 in the checkpoint, 2.0 now", "finished"])


def earlier_checkpoint():
    """A restart from a checkpoint older than the newest sets the later outputs aside, so that the next
    --restart latest continues the new run (not the one it replaced), which ends as the first did."""
    d = os.path.join(work, "earlier")
    run([exe, deck, *common, f"output.dir={d}"], cwd=work)
    old_checkpoints, old_snapshots = files(d, "checkpoint_"), files(d, "snapshot_")
    final_first = hdf5_datasets(os.path.join(d, old_snapshots[-1]))
    with h5py.File(os.path.join(d, "checkpoint_00002.h5")) as f:
        step, count = int(f.attrs["step"]), int(f.attrs["snapshot_count"])
    aside = os.path.join(d, "superseded_00002")
    case("restart from an earlier checkpoint", [exe, "--restart", os.path.join(d, "checkpoint_00002.h5"), deck,
                                                *common, f"output.dir={d}", f"run.max_steps={step + 2}"], 0,
         ["restarting from an earlier checkpoint than the directory's latest", aside])
    moved = sorted(os.listdir(aside)) if os.path.isdir(aside) else []
    later = [f for f in old_checkpoints if int(f[11:16]) > 2] + [f for f in old_snapshots if int(f[9:14]) >= count]
    checks.check(all(f in moved for f in later) and "history.txt" in moved,
                 f"the {len(later)} later checkpoints and snapshots and a copy of history.txt set aside")
    case("--restart latest after it", [exe, "--restart", "latest", deck, *common, f"output.dir={d}"], 0,
         [f"restarted from {os.path.join(d, 'checkpoint_00003.h5')} at step {step + 2}", "finished"])
    final = hdf5_datasets(os.path.join(d, files(d, "snapshot_")[-1]))
    checks.check(final.keys() == final_first.keys() and all(final[k] == final_first[k] for k in final),
                 f"the continued run ends as the first did, bit for bit ({len(final)} datasets)")


def undeletable_checkpoint():
    """An old checkpoint that cannot be deleted (here a directory in its place) is kept with a warning."""
    d = fresh_run("undeletable")
    old = os.path.join(d, "checkpoint_00001.h5")
    os.remove(old)
    os.makedirs(os.path.join(old, "in_the_way"))
    case("an old checkpoint that cannot be deleted", [exe, "--restart", "latest", deck, *common, f"output.dir={d}",
                                                      "output.checkpoints_kept=1"], 0,
         [f"cannot delete the old checkpoint {old}", "finished"])


def main():
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    full_disk_snapshot()
    full_disk_everything()
    full_disk_history()
    dev_full()
    small_tmpfs()
    damaged_checkpoints()
    changed_decks()
    earlier_checkpoint()
    undeletable_checkpoint()
    shutil.rmtree(work, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
