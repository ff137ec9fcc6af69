#!/usr/bin/env python3
"""Ratio of a benchmark counter to its limit, measured back to back.

    ratio.py --bench EXE [--filter REGEX] --counter NAME
             --limit EXE [--limit-filter REGEX] --limit-counter NAME
             [--repetitions 5] [--rounds 3] [--bench-args "..."] [--limit-args "..."]
             --out ratio.json

Example (the grid dust step's modelled bandwidth against STREAM triad):

    python3 perf/ratio.py --bench build/bin/perf/bench_disc_dust --filter 'BM_DustStep/10/' \\
        --counter model_bytes_per_s --limit build/bin/perf/bench_stream --limit-counter bytes_per_s \\
        --repetitions 5 --rounds 3 --out ratio.json

Runs the two Google Benchmark drivers alternately, bench, limit, bench, limit,
... (--rounds times each), every run with --benchmark_repetitions=N, so that
both see the same state of a shared, noisy machine. Each filter must select
exactly one benchmark. From every run it takes the per-repetition values of the
counter and Google Benchmark's median and cv aggregates; the figure of each
side is the median of all its repetitions over all rounds, its spread the
minimum, maximum, quartiles and the per-round medians and cvs. The ratio is
median(bench) / median(limit); the ratios of the paired rounds (round i of
bench over round i of limit) are written too, with their range, as the
honest error bar. The JSON also holds every command, the benchmark names,
the JSON context of each driver (mote_backend, mote_execution_space,
mote_device, host, CPU count, library build type) and the load average
before each run. Prints a one-line summary. Exit status 0; 1 if --max-ratio
or --min-ratio is given and the ratio lies outside it (a FAIL line), or a run
failed; 2 for bad input: arguments (inverted bounds among them), or a filter
or counter that matches nothing usable.
"""
import argparse
import datetime
import json
import os
import shlex
import subprocess
import sys
import tempfile

import numpy as np

CONTEXT_KEYS = ("mote_backend", "mote_execution_space", "mote_device", "host_name", "num_cpus", "mhz_per_cpu",
                "cpu_scaling_enabled", "library_build_type", "executable", "date")


BAD_INPUT, FAILED = 2, 1  # exit statuses


def run_once(exe, filt, counter, repetitions, extra, tmp, tag):
    """One driver run; returns (record, error message or None, exit status for the error)."""
    out = os.path.join(tmp, f"{tag}.json")
    cmd = [exe, f"--benchmark_repetitions={repetitions}", "--benchmark_report_aggregates_only=false",
           f"--benchmark_out={out}", "--benchmark_out_format=json", *extra]
    if filt:
        cmd.insert(1, f"--benchmark_filter={filt}")
    load = list(os.getloadavg())
    start = datetime.datetime.now(datetime.timezone.utc)
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = (datetime.datetime.now(datetime.timezone.utc) - start).total_seconds()
    rec = {"command": shlex.join(cmd), "load_avg_before": load, "wall_s": wall, "returncode": p.returncode}
    if p.returncode != 0 or not os.path.exists(out):
        return rec, f"{shlex.join(cmd)} exited {p.returncode}:\n{p.stderr[-2000:]}", FAILED
    try:
        with open(out) as f:
            data = json.load(f)
    except json.JSONDecodeError:
        return rec, f"{shlex.join(cmd)} wrote no benchmark JSON (does the filter match?):\n{(p.stdout + p.stderr)[-1000:]}", \
            BAD_INPUT
    rec["context"] = {k: data["context"][k] for k in CONTEXT_KEYS if k in data["context"]}
    rec["context"]["load_avg"] = data["context"].get("load_avg")
    benches = data.get("benchmarks", [])
    names = sorted({b.get("run_name", b["name"]) for b in benches})
    if len(names) != 1:
        return rec, f"{exe}: filter {filt!r} selects {len(names)} benchmarks ({', '.join(names) or 'none'}); need " \
            "exactly one", BAD_INPUT
    rec["benchmark"] = names[0]
    its = [b for b in benches if b.get("run_type", "iteration") == "iteration"]
    aggs = {b.get("aggregate_name"): b for b in benches if b.get("run_type") == "aggregate"}
    if not its or counter not in its[0]:
        have = sorted(k for k in (its[0] if its else {}) if isinstance(its[0].get(k), (int, float))) if its else []
        return rec, f"{exe}: no counter {counter!r} in {names[0]} (numeric fields: {', '.join(have)})", BAD_INPUT
    if any(counter not in b for b in its):
        return rec, f"{exe}: {names[0]} lacks {counter!r} in some repetitions (an errored run?)", FAILED
    rec["values"] = [float(b[counter]) for b in its]
    rec["real_time"] = [float(b["real_time"]) for b in its]
    rec["cpu_time"] = [float(b["cpu_time"]) for b in its]
    rec["time_unit"] = its[0].get("time_unit")
    rec["iterations"] = [int(b["iterations"]) for b in its]
    rec["gbench_median"] = float(aggs["median"][counter]) if "median" in aggs else float(np.median(rec["values"]))
    rec["gbench_cv"] = float(aggs["cv"][counter]) if "cv" in aggs else None
    return rec, None, 0


def summary(exe, filt, counter, runs):
    values = np.array([v for r in runs for v in r["values"]])
    q1, med, q3 = np.percentile(values, [25, 50, 75])
    return {
        "executable": exe, "filter": filt, "counter": counter, "benchmark": runs[0]["benchmark"],
        "median": float(med), "min": float(values.min()), "max": float(values.max()),
        "quartiles": [float(q1), float(q3)], "iqr_over_median": float((q3 - q1) / med),
        "round_medians": [r["gbench_median"] for r in runs], "round_cv": [r["gbench_cv"] for r in runs],
        "cpu_over_real_time": float(np.median([c / t for r in runs for c, t in zip(r["cpu_time"], r["real_time"])])),
        "samples": int(values.size), "context": runs[0]["context"], "runs": runs,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bench", required=True, help="benchmark driver")
    ap.add_argument("--filter", default=None, help="--benchmark_filter for the driver (must select one benchmark)")
    ap.add_argument("--counter", required=True, help="user counter of the benchmark, e.g. model_bytes_per_s")
    ap.add_argument("--limit", required=True, help="driver measuring the limit, e.g. bench_stream")
    ap.add_argument("--limit-filter", default=None)
    ap.add_argument("--limit-counter", required=True, help="its counter, e.g. bytes_per_s")
    ap.add_argument("--repetitions", type=int, default=5, help="--benchmark_repetitions of every run")
    ap.add_argument("--rounds", type=int, default=3, help="alternations bench, limit (each round runs both once)")
    ap.add_argument("--bench-args", default="", help="extra arguments of the benchmark driver (one string)")
    ap.add_argument("--limit-args", default="", help="extra arguments of the limit driver (one string)")
    ap.add_argument("--out", required=True, help="JSON file to write")
    ap.add_argument("--max-ratio", type=float, default=None,
                    help="a bound to check: exit status 1 if the ratio of the medians exceeds it")
    ap.add_argument("--min-ratio", type=float, default=None,
                    help="a bound to check: exit status 1 if the ratio of the medians is below it")
    args = ap.parse_args()
    if args.repetitions < 1 or args.rounds < 1:
        ap.error("--repetitions and --rounds must be >= 1")
    if args.max_ratio is not None and args.min_ratio is not None and args.min_ratio > args.max_ratio:
        ap.error(f"--min-ratio {args.min_ratio} exceeds --max-ratio {args.max_ratio}: no ratio could pass")

    sides = {"bench": (args.bench, args.filter, args.counter, shlex.split(args.bench_args)),
             "limit": (args.limit, args.limit_filter, args.limit_counter, shlex.split(args.limit_args))}
    runs = {"bench": [], "limit": []}
    with tempfile.TemporaryDirectory(prefix="mote_ratio_") as tmp:
        for i in range(args.rounds):
            for side in ("bench", "limit"):
                exe, filt, counter, extra = sides[side]
                rec, err, status = run_once(exe, filt, counter, args.repetitions, extra, tmp, f"{side}_{i}")
                if err:
                    print(f"ratio.py: {err}", file=sys.stderr)
                    return status
                runs[side].append(rec)
                print(f"round {i + 1}/{args.rounds} {side}: {rec['benchmark']} {counter} median "
                      f"{rec['gbench_median']:.4e} (cv {rec['gbench_cv'] or 0:.1%}), load {rec['load_avg_before'][0]:.2f}",
                      flush=True)
    bench = summary(*sides["bench"][:3], runs["bench"])
    limit = summary(*sides["limit"][:3], runs["limit"])
    paired = [b / l for b, l in zip(bench["round_medians"], limit["round_medians"])]
    same = all(bench["context"].get(k) == limit["context"].get(k)
               for k in ("mote_backend", "mote_execution_space", "mote_device", "host_name"))
    result = {
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "command": shlex.join([sys.executable, *sys.argv]),
        "cwd": os.getcwd(),
        "repetitions": args.repetitions, "rounds": args.rounds, "order": "bench, limit, alternating",
        "ratio": bench["median"] / limit["median"],
        "round_ratios": paired, "round_ratio_min": min(paired), "round_ratio_max": max(paired),
        "same_context": same,
        "max_ratio": args.max_ratio, "min_ratio": args.min_ratio,
        "backend": bench["context"].get("mote_backend"),
        "execution_space": bench["context"].get("mote_execution_space"),
        "device": bench["context"].get("mote_device"),
        "bench": bench, "limit": limit,
    }
    with open(args.out, "w") as f:
        json.dump(result, f, indent=1)
        f.write("\n")
    print(f"{bench['benchmark']} {args.counter} median {bench['median']:.4e} "
          f"[{bench['min']:.3e}, {bench['max']:.3e}] / {limit['benchmark']} {args.limit_counter} median "
          f"{limit['median']:.4e} [{limit['min']:.3e}, {limit['max']:.3e}] = {result['ratio']:.4f} "
          f"(paired rounds {min(paired):.4f}-{max(paired):.4f}; {result['execution_space'] or result['backend']}, "
          f"{result['device']}); wrote {args.out}")
    if not same:
        print("ratio.py: warning: the two drivers report different back-ends or devices", file=sys.stderr)
    return check_bounds(result["ratio"], args.max_ratio, args.min_ratio)


def check_bounds(ratio, max_ratio, min_ratio):
    """0 if ratio lies within the bounds given (none: 0), else 1, with a PASS/FAIL line."""
    if max_ratio is None and min_ratio is None:
        return 0
    ok = (max_ratio is None or ratio <= max_ratio) and (min_ratio is None or ratio >= min_ratio)
    bounds = " and ".join(b for b in (f"<= {max_ratio}" if max_ratio is not None else "",
                                      f">= {min_ratio}" if min_ratio is not None else "") if b)
    print(f"{'PASS' if ok else 'FAIL'} ratio {ratio:.4f} ({bounds})")
    return 0 if ok else FAILED


if __name__ == "__main__":
    sys.exit(main())
