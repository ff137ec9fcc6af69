"""VALIDATION E3: growth-fragmentation steady state at 20 au (RBO24 Fig. 10):
steady, mass conserved to 1e-10, cut-off at the fragmentation limit; and what
Fig. 10 shows that needs no outside data:
  * the steady state does not depend on the initial distribution: the deck's
    MRN up to 1 micron, MRN up to 100 micron (most of the mass near the
    cut-off: the steady state is approached from above) and all of the mass in
    the smallest bin reach the same sigma_d(m) to a relative L1 of MAX_L1;
  * the cut-off moves as a_frag ~ v_frag^2: a run at v_frag / sqrt(2) has its
    cut-off (sigma_d down to 1e-2 of its peak, check.py) a factor 2 lower, to
    SCALING_TOL. The measured ratio is 1.93, not 2: the settling-speed
    difference of the vertically integrated kernel (RBO24 sec. 5.1) adds a
    relative velocity that does not scale with v_frag, which the a_frag
    estimate (Birnstiel et al. 2012) leaves out;
  * a coarse mass grid, 23 species (m_k+1 / m_k = 2.76, as the reduced
    transition_disc deck's 33 over its wider range), peaks where the fine grid
    does: a_peak within PEAK_TOL (a bin of the coarse grid is a factor 1.40 in
    size). The peak sits at the fragmentation barrier itself, not at BKE12's
    two-population size f_f a_frag (f_f = 0.37): transition_disc's check.py
    compares with the barrier for that reason.

    coag_steady_state.py COAG_STEADY_STATE_EXE WORK_DIR [full]
The default (CI) variant runs 100 species to 5e4 yr; `full` runs the deck as
published (200 species, 1e5 yr) and writes fig10.png. Both take seconds."""
import math
import os
import re
import shutil
import sys

from harness import Checks, run, ROOT

exe, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)  # a fresh directory per run: output.dir belongs to one run
full = len(sys.argv) > 3 and sys.argv[3] == "full"
deck = os.path.join(ROOT, "problems", "coag_steady_state", "coag_steady_state.toml")
check_py = os.path.join(ROOT, "problems", "coag_steady_state", "check.py")
c = Checks()
# Measured (Serial, default product split): L1 between the initial states 1.5e-4 and 1.3e-3 (CI), 2.1e-3 and
# 1.5e-3 (full). That is the floor the time integration leaves (rel_tol 1e-2): from 5e4 yr on, sigma_d of one
# run changes by 3e-4 to 1.2e-3 from one snapshot to the next, and the L1 between the runs wanders between
# 1e-3 and 2.1e-3; it is 7e-3 at 3.5e4 yr and 0.1 at 2.5e4 yr, before the steady state. The cut-off ratio
# is 0.517 against 0.5 (+3.5 %, both variants). The bounds leave a margin of about 2.4 and 2.9.
MAX_L1 = 5e-3
SCALING_TOL = 0.1
PEAK_TOL = 1.25
V_FRAG = 100.0


def steady(name, *overrides, compare=(), species=None):
    out = os.path.join(work, name)
    args = [exe, deck, f"output.dir=\"{out}\""]
    if not full:
        args += ["coagulation.species=100", "run.t_end=1.57788e12", "output.snapshot_dt=1.57788e11"]
    if species:
        args.append(f"coagulation.species={species}")
    run(args + list(overrides))
    cmd = [sys.executable, check_py, out, "--mass-tol", "1e-10", *compare]
    if full and name == "mrn_1um":
        cmd += ["--plot", os.path.join(work, "fig10.png")]
    p = run(cmd, expect=None)
    print(p.stdout.strip())
    c.check(p.returncode == 0, f"coag_steady_state {name}: steady, conserved to 1e-10, cut-off at the fragmentation limit"
            + (" and " + " ".join(compare) if compare else ""))
    return out, float(re.search(r"a_peak = ([0-9.eE+-]+) cm", p.stdout).group(1))


base, peak = steady("mrn_1um")
same = ["--same-as", base, "--max-l1", str(MAX_L1)]
steady("mrn_100um", "disc.a_init_max=1e-2", compare=same)
steady("smallest_bin", "disc.a_init_max=5e-5", compare=same)
steady("v_frag_low", f"coagulation.v_frag={V_FRAG / math.sqrt(2)!r}",
       compare=["--scaling", base, "--scaling-tol", str(SCALING_TOL)])
_, coarse_peak = steady("coarse_grid", species=23)
c.check(1 / PEAK_TOL <= coarse_peak / peak <= PEAK_TOL,
        f"23 species: a_peak = {coarse_peak:.4e} cm against {peak:.4e} cm with the deck's grid, ratio "
        f"{coarse_peak / peak:.4f} within a factor {PEAK_TOL}")
sys.exit(c.finish())
