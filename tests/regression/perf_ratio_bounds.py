#!/usr/bin/env python3
"""perf/ratio.py as a check (perf/README.md): with --max-ratio / --min-ratio it
prints a PASS or FAIL line and exits 1 when the ratio of the medians lies
outside the bounds, 0 inside them, and 2 (bad input) when a driver's counter
is missing or the bounds are inverted.
Two stand-in drivers write fixed Google Benchmark JSON (counter 5 and 4 in
every repetition), so the ratio is exactly 1.25 and nothing is timed.

usage: perf_ratio_bounds.py WORKDIR
"""
import os
import shutil
import stat
import sys

from harness import ROOT, Checks, run

work = sys.argv[1]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
DRIVER = '''#!{python}
import json, sys
args = dict(a.split("=", 1) for a in sys.argv[1:] if "=" in a)
reps = int(args.get("--benchmark_repetitions", "1"))
run = {{"name": "BM_Fixed", "run_name": "BM_Fixed", "run_type": "iteration", "iterations": 1,
        "real_time": 1.0, "cpu_time": 1.0, "time_unit": "ms", "{counter}": {value}}}
with open(args["--benchmark_out"], "w") as f:
    json.dump({{"context": {{"host_name": "stand-in"}}, "benchmarks": [run] * reps}}, f)
'''


def driver(name, counter, value):
    path = os.path.join(work, name)
    with open(path, "w") as f:
        f.write(DRIVER.format(python=sys.executable, counter=counter, value=value))
    os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR)
    return path


bench, limit = driver("bench", "rate", 5.0), driver("limit", "rate", 4.0)
ratio_py = os.path.join(ROOT, "perf", "ratio.py")
common = [sys.executable, ratio_py, "--bench", bench, "--counter", "rate", "--limit", limit, "--limit-counter", "rate",
          "--repetitions", "3", "--rounds", "2", "--out", os.path.join(work, "ratio.json")]
checks = Checks()
inside = run(common + ["--max-ratio", "1.3", "--min-ratio", "1.2"], expect=None)
checks.check(inside.returncode == 0 and "PASS ratio 1.2500" in inside.stdout,
             f"ratio 1.25 within [1.2, 1.3]: exit {inside.returncode}, a PASS line")
above = run(common + ["--max-ratio", "1.2"], expect=None)
checks.check(above.returncode == 1 and "FAIL ratio 1.2500 (<= 1.2)" in above.stdout,
             f"ratio 1.25 above --max-ratio 1.2: exit {above.returncode}, a FAIL line")
below = run(common + ["--min-ratio", "1.5"], expect=None)
checks.check(below.returncode == 1 and "FAIL ratio 1.2500 (>= 1.5)" in below.stdout,
             f"ratio 1.25 below --min-ratio 1.5: exit {below.returncode}, a FAIL line")
missing = run(common[:4] + ["--counter", "other"] + common[6:] + ["--max-ratio", "2"], expect=None)
checks.check(missing.returncode == 2 and "no counter 'other'" in missing.stdout + missing.stderr,
             f"a counter the driver does not report: exit {missing.returncode} (2), naming it")
inverted = run(common + ["--max-ratio", "1.2", "--min-ratio", "1.3"], expect=None)
checks.check(inverted.returncode == 2 and "exceeds --max-ratio" in inverted.stderr,
             f"--min-ratio above --max-ratio: exit {inverted.returncode} (2), before any run")
sys.exit(checks.finish())
