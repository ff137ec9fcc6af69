#!/usr/bin/env python3
"""Model years per wall-clock second of a transition_disc deck (RBO24 sec. 7, issue 20).

    transition_disc_rate.py --exe build/bin/transition_disc --deck DECK [--ranks 2] [--steps 2000]
                            [--from RUN_DIR] [--repeat 3] [--out rate.json]

Runs the deck `--repeat` times for `--steps` steps (mpirun with `--ranks`), each
in a fresh output directory, from t = 0 or, with --from, from the newest
checkpoint of a copy of RUN_DIR (the late, steady phase has other time-steps).
From the run's own log (its closing line: steps and time; its timers table:
the seconds spent in the steps and their time-step computations, without the
set-up, the restart's read and the output) and the history columns dust_seconds, <solver>_seconds, it reports per
repetition and as medians: steps/s, model years per second of stepping, the
fractions of the stepping time in the dust dynamics and each sub-solver, the mean time-step,
and the wall time 1 Myr would take at that pace. JSON out; the machine's load
average before each repetition is recorded with it (quote medians: the
machine is shared).
"""
import argparse
import json
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import mote  # noqa: E402

YEAR_S = 3.15576e7
LOOP_LINE = re.compile(r"(?:finished|stopped at run\.max_steps): (\d+) steps, t = (\S+) in (\S+) s")
LOOP_TIMER = re.compile(r"^(step|dt)\s+(\d+)\s+(\S+)\s", re.M)  # the timers table's rows: calls, seconds


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()


def time_unit_s(run_dir):
    """Seconds per code time unit, from the run's newest checkpoint (the unit system as run, overrides included)."""
    import h5py

    names = sorted(n for n in os.listdir(run_dir) if n.startswith("checkpoint_") and n.endswith(".h5"))
    if not names:
        raise SystemExit(f"{run_dir}: no checkpoint to read the unit system from")
    with h5py.File(os.path.join(run_dir, names[-1]), "r") as f:
        return float(f.attrs["unit_time_s"])


def prepare(run_dir, source):
    """A fresh output directory, or a copy of `source` with its newest checkpoint (returned)."""
    if source is None:
        return None
    shutil.copytree(source, run_dir)
    lock = os.path.join(run_dir, "run.lock")
    if os.path.exists(lock):
        os.remove(lock)
    names = sorted(n for n in os.listdir(run_dir) if n.startswith("checkpoint_") and n.endswith(".h5"))
    if not names:
        raise SystemExit(f"no checkpoint in {source}")
    return os.path.join(run_dir, names[-1])


def one_run(args, tmp, k):
    run_dir = os.path.join(tmp, f"run{k}")
    checkpoint = prepare(run_dir, args.from_dir)
    start_step, start_time = 0, 0.0
    if checkpoint:
        import h5py

        with h5py.File(checkpoint, "r") as f:
            start_step, start_time = int(f.attrs["step"]), float(f.attrs["time"])
    cmd = ["mpirun", "--oversubscribe", "-np", str(args.ranks)] if args.ranks > 1 else []
    cmd += [args.exe] + (["--restart", checkpoint] if checkpoint else []) + [args.deck, f"output.dir={run_dir}"]
    # One history row, at the end: a row every step would time the history's reductions and writes,
    # which on a GPU cost several dust steps.
    every = start_step + args.steps
    cmd += [f"run.max_steps={start_step + args.steps}", f"output.history_every={every}",
            "output.checkpoint_wall=0", "run.progress_interval=1e9"]
    if checkpoint is None:
        cmd.append("output.overwrite=true")
    load = os.getloadavg()[0]
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if p.returncode != 0 or not LOOP_LINE.search(p.stdout) or "timers:" not in p.stdout:
        raise SystemExit(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stdout[-2000:]}\n{p.stderr[-2000:]}")
    m = LOOP_LINE.search(p.stdout)
    steps, wall = int(m.group(1)), float(m.group(3))
    # The time loop without its output: the steps and their time-step computations (the dynamics'
    # and the sub-solvers' *_seconds count both).
    timers = {m.group(1): (int(m.group(2)), float(m.group(3)))
              for m in LOOP_TIMER.finditer(p.stdout, p.stdout.rfind("timers:"))}
    if timers.get("step", (0,))[0] != steps:
        raise SystemExit(f"{run_dir}: the step timer counts {timers.get('step')}, the run {steps} steps")
    stepping = sum(seconds for _, seconds in timers.values())
    h = mote.read_history(os.path.join(run_dir, "history.txt"))
    last = h[-1]
    if int(last["step"]) != start_step + steps:
        raise SystemExit(f"history of {run_dir} ends at step {last['step']}, not {start_step + steps}")
    model_yr = (last["time"] - start_time) * time_unit_s(run_dir) / YEAR_S
    # The *_seconds columns count the wall time of this process (they start at 0 on a restart).
    solvers = [n[: -len("_seconds")] for n in h.dtype.names if n.endswith("_seconds")]
    fractions = {n: float(last[n + "_seconds"]) / stepping for n in solvers}
    shutil.rmtree(run_dir, ignore_errors=True)
    return {"steps": steps, "wall_s": wall, "stepping_s": stepping, "steps_per_s": steps / stepping,
            "model_yr": model_yr, "model_yr_per_s": model_yr / stepping, "mean_dt_yr": model_yr / steps,
            "fractions": fractions, "wall_h_per_Myr": 1e6 / (model_yr / stepping) / 3600, "load_before": load,
            "command": cmd}


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--exe", required=True)
    p.add_argument("--deck", required=True)
    p.add_argument("--ranks", type=int, default=1)
    p.add_argument("--steps", type=int, default=2000)
    p.add_argument("--from", dest="from_dir")
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--out")
    args = p.parse_args()
    if args.steps < 1 or args.repeat < 1 or args.ranks < 1:
        p.error("--steps, --repeat and --ranks must be at least 1")
    with tempfile.TemporaryDirectory(prefix="mote_td_rate_") as tmp:
        runs = [one_run(args, tmp, k) for k in range(args.repeat)]
    med = {key: statistics.median(r[key] for r in runs) for key in ("steps_per_s", "model_yr_per_s", "mean_dt_yr")}
    # From the median rate, not a median of its own: with an even --repeat the two medians disagree.
    med["wall_h_per_Myr"] = 1e6 / med["model_yr_per_s"] / 3600.0
    med["fractions"] = {n: statistics.median(r["fractions"][n] for r in runs) for n in runs[0]["fractions"]}
    result = {"deck": args.deck, "ranks": args.ranks, "steps": args.steps, "from": args.from_dir,
              "cpu": cpu_model(), "cores": os.cpu_count(), "median": med, "runs": runs}
    text = json.dumps(result, indent=2)
    if args.out:
        with open(args.out, "w") as f:
            f.write(text + "\n")
    print(f"{os.path.basename(args.deck)}, {args.ranks} rank(s), {args.steps} steps"
          f"{' from ' + args.from_dir if args.from_dir else ''}: median {med['steps_per_s']:.1f} steps/s, "
          f"{med['model_yr_per_s']:.3g} model yr/s (mean dt {med['mean_dt_yr']:.3g} yr), "
          f"{med['wall_h_per_Myr']:.3g} h per Myr; "
          + ", ".join(f"{n} {f:.1%}" for n, f in med["fractions"].items()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
