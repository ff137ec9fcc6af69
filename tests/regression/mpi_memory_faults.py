#!/usr/bin/env python3
"""Rank 0 running out of memory while it builds a file stops every rank together (issue 22).

    mpi_memory_faults.py EXE FAIL_ALLOC_LIBRARY WORKDIR LAUNCHER...

Rank 0 holds a whole snapshot or checkpoint in memory while it builds it from its own block and the
blocks the other ranks send. Runs gaussian_pulse (512 x 512: 2 MiB per field, about 1 MiB per field and
rank, an 8 MiB snapshot, a 2 MiB checkpoint) on 2 ranks for 2 steps, then restarts it with rank 0's heap
allocations made to fail (FAIL_ALLOC_LIBRARY under LD_PRELOAD, rank 0 alone):
  * every allocation of at least 4 MiB: HDF5 cannot grow the snapshot's image. Exit 5, the error names
    the snapshot, a checkpoint (2 MiB) is written before stopping;
  * every allocation of exactly the size of rank 1's block of a 512 x 512 dataset as sent to rank 0:
    rank 0 refuses that block. Exit 5, the error names the snapshot and the block; the checkpoint before
    stopping cannot be written either (it holds such a block);
  * every allocation of at least 1.5 MiB: the snapshot writer's node coordinates of rank 0 (2.1 MiB)
    cannot be allocated, outside any agreement of the ranks. Rank 0 ends every rank (MPI_Abort, exit 1)
    with one error line: out of memory on rank 0.
Each case must end within a time limit (no rank left waiting for the other), leave no temporary or
lock file, no new snapshot, the earlier files unchanged (checksums), and the run then restarts on 2
ranks from its newest checkpoint.
Ends with 'N passed, M failed'.
"""
import os
import shutil
import sys

from harness import MPI_ENV, Checks, checksums, files, run_within

IO_ERROR = 5  # docs/quickstart.md, include/mote/core/exit_codes.hpp
INTERNAL_ERROR = 1
TIME_LIMIT = 120  # seconds; a run still going then has ranks waiting for each other
RANK0_OPTION = "--rank0-preload"
N = 512  # cells per direction; the grid is split in y between the 2 ranks

if len(sys.argv) > 1 and sys.argv[1] == RANK0_OPTION:  # runs as a rank process
    library, cmd = sys.argv[2], sys.argv[3:]
    env = dict(os.environ)
    if env.get("OMPI_COMM_WORLD_RANK") == "0":
        env["LD_PRELOAD"] = library
    os.execve(cmd[0], cmd, env)

exe, library, work, launcher = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
deck = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "problems", "gaussian_pulse",
                                    "gaussian_pulse.toml"))
common = [deck, f"grid.nx={N}", f"grid.ny={N}", "output.snapshot_dt=0.001", "output.checkpoint_every=100",
          "run.progress_interval=0", "transport.diffusivity=1e-3"]
ENV = dict(os.environ, **MPI_ENV, PMIX_MCA_gds="hash", OMPI_MCA_btl="self,tcp")
checks = Checks()


def mpirun(args, failing=None):
    """exe on 2 ranks; `failing` ({variable: bytes}) makes rank 0's allocations fail."""
    env = dict(ENV, **{k: str(v) for k, v in (failing or {}).items()})
    wrapper = [sys.executable, os.path.abspath(__file__), RANK0_OPTION, library] if failing else []
    return run_within([*launcher, *wrapper, exe, *args], TIME_LIMIT, env=env, cwd=work)


def case(name, failing, exit_code, in_error, in_output, new_checkpoint):
    """A 2-rank run of 2 steps, then a restart whose rank 0 runs out of memory (`failing`); checks the
    exit code, one error line naming the next snapshot and holding every `in_error` text, every
    `in_output` text, no temporary or lock file, the earlier files unchanged, a new checkpoint written
    before stopping or not (`new_checkpoint`), and a restart from the newest checkpoint."""
    d = os.path.join(work, name.replace(" ", "_"))
    rc, text = mpirun([*common, f"output.dir={d}", "run.max_steps=2"])
    if rc != 0:
        raise AssertionError(f"the first part of {name} exited {rc}\n{text[-3000:]}")
    before, ckpts = checksums(d, ("history.txt",)), files(d, "checkpoint_")
    next_snapshot = f"snapshot_{len(files(d, 'snapshot_')):05d}.h5"
    rc, text = mpirun(["--restart", "latest", *common, f"output.dir={d}", "run.max_steps=6"], failing)
    checks.check(rc == exit_code, f"{name}: mpirun exits {rc} == {exit_code}" +
                 ("" if rc == exit_code else f"\n{text[-3000:]}"))
    errors = [line for line in text.splitlines() if "error: " in line]
    checks.check(len(errors) == 1 and all(e in errors[0] for e in in_error),
                 f"{name}: one error line holding {in_error} ({errors})")
    for e in in_output:
        checks.check(e in text, f"{name}: the output says {e!r}")
    left = [f for f in os.listdir(d) if f.endswith(".tmp") or f == "run.lock"]
    checks.check(not left, f"{name}: no temporary or lock file left ({left})")
    checks.check(not os.path.exists(os.path.join(d, next_snapshot)), f"{name}: no {next_snapshot}")
    after = checksums(d, ("history.txt",))
    checks.check({n: s for n, s in after.items() if n in before} == before, f"{name}: earlier files unchanged")
    new = [f for f in files(d, "checkpoint_") if f not in ckpts]
    checks.check(len(new) == (1 if new_checkpoint else 0), f"{name}: new checkpoints {new}")
    last = files(d, "checkpoint_")[-1]
    rc, text = mpirun(["--restart", "latest", *common, f"output.dir={d}", "run.max_steps=8"])
    ok = rc == 0 and f"restarted from {os.path.join(d, last)}" in text and "stopped at run.max_steps" in text
    checks.check(ok, f"{name}: restarts on 2 ranks from {last} and steps on to run.max_steps = 8" +
                 ("" if ok else f" (exit {rc})\n{text[-3000:]}"))


def main():
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    snapshot = "snapshot_00002.h5"
    case("snapshot image", {"MOTE_FAIL_ALLOC_AT_LEAST": 4 << 20}, IO_ERROR,
         [snapshot, "unable to allocate memory block"], ["writing a checkpoint before stopping"], True)
    block_message = 2 * 2 * 8 + (N // 2) * N * 8  # offset and count (2 x 2 hsize_t), then the doubles
    case("block of rank 1", {"MOTE_FAIL_ALLOC_OF": block_message}, IO_ERROR,
         [snapshot, "out of memory for rank 1's block of /fields/density"],
         ["the checkpoint could not be written either"], False)
    case("buffer of rank 0", {"MOTE_FAIL_ALLOC_AT_LEAST": 3 << 19}, INTERNAL_ERROR,
         ["out of memory (std::bad_alloc) on rank 0: stopping every rank"], [], False)
    shutil.rmtree(work, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
