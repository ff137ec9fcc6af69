#!/usr/bin/env python3
"""Exit codes and messages of the problem executables (issue 22; the table in docs/quickstart.md).

    exit_codes.py BIN_DIR PROBLEMS_DIR WORKDIR

Runs gaussian_pulse (grid) and sph_sod (SPH) on decks that must fail, and the
command-line requests that must not start a run:
  * non-finite reals and integers outside their C++ type: exit 2, the key, where it came from and the range;
  * a directory given as the deck, a key without '=', a type error on a required key: exit 2, the right message;
  * --check with several cross-key errors: exit 2, every error with its file and line;
  * a time-step below run.dt_min, in the grid and in the SPH engine: exit 3, the limiting constraint named;
  * a missing checkpoint to restart from: exit 2; an output directory that cannot be created: exit 5;
  * --version prints the version, --help starts with mote's own usage and shows no Kokkos banner.
Every failing case must leave its output directory absent. Ends with 'N passed, M failed'.
"""
import os
import shutil
import sys

from harness import Checks, run

BAD_INPUT, NUMERICAL, IO_ERROR = 2, 3, 5  # docs/quickstart.md, include/mote/core/exit_codes.hpp

PULSE = """[run]
t_end = 0.01
[output]
dir = "{out}"
[grid]
nx = 16
ny = 16
[transport]
diffusivity = 0.01
[pulse]
t0 = 0.5
"""


def main():
    bin_dir, problems, work = sys.argv[1:4]
    pulse, sod = os.path.join(bin_dir, "gaussian_pulse"), os.path.join(bin_dir, "sph_sod")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    checks = Checks()

    def write_deck(name, text):
        out = os.path.join(work, "out_" + name)
        deck = os.path.join(work, name + ".toml")
        with open(deck, "w") as f:
            f.write(text.format(out=out))
        return deck, out

    def case(name, cmd, code, expected, absent=(), out=None):
        p = run(cmd, expect=None, cwd=work)
        text = p.stdout + p.stderr
        checks.check(p.returncode == code, f"{name}: exit code {p.returncode} == {code}")
        for e in expected:
            checks.check(e in text, f"{name}: message contains {e!r}" + ("" if e in text else f"\n{text[-1500:]}"))
        for a in absent:
            checks.check(a not in text, f"{name}: message does not contain {a!r}")
        if out is not None:
            checks.check(not os.path.exists(out), f"{name}: no output directory")
        return p

    good, good_out = write_deck("good", PULSE)
    case("t_end=inf", [pulse, good, "run.t_end=inf"], BAD_INPUT,
         ["command line 'run.t_end=inf': key 'run.t_end': value inf is not finite"], out=good_out)
    inf_deck, inf_out = write_deck("diffusivity_inf", PULSE.replace("diffusivity = 0.01", "diffusivity = inf"))
    case("diffusivity = inf", [pulse, inf_deck], BAD_INPUT,
         [inf_deck + ":9: key 'transport.diffusivity': value inf is not finite"], out=inf_out)
    case("nx=3000000000", [pulse, good, "grid.nx=3000000000"], BAD_INPUT,
         ["key 'grid.nx': value 3000000000 does not fit the key's C++ type int (-2147483648 to 2147483647)"],
         out=good_out)
    case("directory as deck", [pulse, work], BAD_INPUT, ["is a directory"], ["missing required key"])
    case("key without =", [pulse, good, "grid.nx"], BAD_INPUT, ["an override needs a value: grid.nx=VALUE"],
         ["more than one deck"], out=good_out)
    typed, typed_out = write_deck("typed", PULSE.replace("diffusivity = 0.01", 'diffusivity = "fast"'))
    case("type error on a required key", [pulse, typed], BAD_INPUT,
         ["key 'transport.diffusivity': expected real", "(1 error)"], ["missing required key"], out=typed_out)

    crossed, crossed_out = write_deck("crossed", PULSE.replace("ny = 16", "ny = 16\nx_min = 2.0\ny_max = -1.0"))
    case("--check, cross-key errors", [pulse, crossed, "--check"], BAD_INPUT,
         ["(2 errors)", crossed + " (default): key 'grid.x_max': must exceed grid.x_min = 2.0 (" + crossed + ":8)",
          crossed + ":9: key 'grid.y_max': must exceed grid.y_min = 0.0"], out=crossed_out)

    case("grid dt below run.dt_min", [pulse, good, "run.dt_min=1.0"], NUMERICAL,
         ["limited by the advection-diffusion CFL (scheme.cfl), is below run.dt_min = 1"])
    sod_out = os.path.join(work, "out_sod")
    case("SPH dt below run.dt_min",
         [sod, os.path.join(problems, "sph_sod", "sph_sod.toml"), "output.dir=" + sod_out, "run.dt_min=1.0",
          "output.snapshot_dt=0.0"],
         NUMERICAL, ["limited by the SPH gas Courant/force/damping condition", "is below run.dt_min = 1"])
    cadence_out = os.path.join(work, "out_cadence")
    case("snapshot cadence below run.dt_min",
         [sod, os.path.join(problems, "sph_sod", "sph_sod.toml"), "output.dir=" + cadence_out, "run.dt_min=1.0"],
         BAD_INPUT, ["key 'output.snapshot_dt': 0.05 is below the smallest allowed time-step, run.dt_min = 1"],
         out=cadence_out)

    case("missing checkpoint", [pulse, good, "--restart", os.path.join(work, "checkpoint_00009.h5")], BAD_INPUT,
         ["cannot restart from checkpoint"])
    case("output directory inside a file", [pulse, good, "output.dir=/dev/null/out"], BAD_INPUT,
         ["key 'output.dir': '/dev/null' exists and is not a directory"])
    case("output directory not writable", [pulse, good, "output.dir=/sys/mote_out"], IO_ERROR,
         ["cannot create output directory '/sys/mote_out'"])

    p = case("--version", [pulse, "--version"], 0, ["mote "])
    checks.check(p.stdout.startswith("mote "), "--version: the first line is the version")
    p = case("--help", [pulse, "--help"], 0, ["usage: gaussian_pulse", "deck keys:", "dt_min (real)"])
    checks.check(p.stdout.startswith("gaussian_pulse: ") and "Kokkos command line arguments" not in p.stdout,
                 "--help: mote's own help first, without the Kokkos banner")
    p = case("--kokkos-help", [pulse, "--kokkos-help"], 0, ["Kokkos command line arguments"], ["no deck given"])
    shutil.rmtree(work, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
