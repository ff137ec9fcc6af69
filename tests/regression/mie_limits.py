"""The Mie generator (python/mote/mie.py) against independent checks: the
cross-sections and g from the series against the integrated phase function
(|S1|^2 + |S2|^2) and the optical theorem, Bohren & Huffman's published
sample case (which fixes the series' coefficients), the Rayleigh limit, the
extinction paradox (Q_ext -> 2), Q_abs = 0 for a real index, and the table
format mote::radiation::read_dsharp_table reads.
Usage: mie_limits.py <python dir> <work dir>"""

import os
import sys

import numpy as np

sys.path.insert(0, sys.argv[1])
from mote import mie  # noqa: E402

failures = []
checks = []


def check(name, ok, detail):
    print(("PASS " if ok else "FAIL ") + name + ": " + detail)
    checks.append(name)
    if not ok:
        failures.append(name)


mu, w = np.polynomial.legendre.leggauss(600)
for x, m in [(0.5, 1.5 + 0.01j), (3.0, 1.7 + 0.1j), (10.0, 1.33 + 0.0j), (25.0, 2.0 + 1.0j)]:
    q_ext, q_sca, g = mie.efficiencies(x, m)
    s1, s2 = mie.scattering_amplitudes(x, m, mu)
    p = abs(s1) ** 2 + abs(s2) ** 2
    q_sca_int = np.sum(w * p) / x ** 2
    g_int = np.sum(w * mu * p) / np.sum(w * p)
    s0 = mie.scattering_amplitudes(x, m, np.array([1.0]))[0][0]
    q_ext_theorem = 4.0 / x ** 2 * s0.real
    check(f"phase function x={x} m={m}",
          abs(q_sca_int / q_sca - 1) < 1e-8 and abs(g_int - g) < 1e-8 and abs(q_ext_theorem / q_ext - 1) < 1e-10,
          f"Q_sca {q_sca:.8g} vs {q_sca_int:.8g}, g {g:.8g} vs {g_int:.8g}, Q_ext {q_ext:.8g} vs {q_ext_theorem:.8g}")

# Bohren & Huffman's BHMIE sample case (a sphere of radius 0.525 um in light of
# 0.6328 um, m = 1.55): Q_ext = Q_sca = 3.10543, to the six digits it prints.
q_ext, q_sca, g = mie.efficiencies(2 * np.pi * 0.525 / 0.6328, 1.55 + 0.0j)
check("Bohren & Huffman's BHMIE sample x=5.213 m=1.55", abs(q_ext - 3.10543) < 5e-6 and abs(q_sca - 3.10543) < 5e-6,
      f"Q_ext {q_ext:.6f}, Q_sca {q_sca:.6f} against 3.10543")

x, m = 0.01, 1.5 + 0.1j
q_ext, q_sca, g = mie.efficiencies(x, m)
pol = (m * m - 1) / (m * m + 2)
q_abs_r, q_sca_r = 4 * x * pol.imag, 8.0 / 3.0 * x ** 4 * abs(pol) ** 2
check("Rayleigh limit x=0.01", abs((q_ext - q_sca) / q_abs_r - 1) < 1e-3 and abs(q_sca / q_sca_r - 1) < 1e-3
      and abs(g) < 1e-3, f"Q_abs {q_ext - q_sca:.6g} vs {q_abs_r:.6g}, Q_sca {q_sca:.6g} vs {q_sca_r:.6g}, g {g:.2g}")

q_500 = mie.efficiencies(500.0, 1.5 + 0.5j)[0]
q_ext = mie.efficiencies(2000.0, 1.5 + 0.5j)[0]
# Q_ext -> 2 from above, with the edge term ~ 2 x^(-2/3) (van de Hulst 1957)
check("extinction paradox x=500, 2000", 2.0 < q_ext < q_500 and abs(q_ext - 2.0) < 0.02,
      f"Q_ext {q_500:.6f}, {q_ext:.6f}")

q_ext, q_sca, g = mie.efficiencies(7.0, 1.6 + 0.0j)
check("no absorption for a real index", abs(q_ext - q_sca) < 1e-10 * q_ext, f"Q_ext - Q_sca = {q_ext - q_sca:.3g}")

os.makedirs(sys.argv[2], exist_ok=True)
path = os.path.join(sys.argv[2], "mie_table.dat")
sizes, lams = [1e-5, 1e-4, 1e-3], [0.5, 5.0, 50.0, 500.0]
mie.write_dsharp_table(path, sizes, lams, 1.7 + 0.03j, 3.0)
lines = open(path).read().split("\n")
rows = np.loadtxt(path, skiprows=1)
check("table format", lines[0] == "3 4" and rows.shape == (12, 5) and np.all(rows[:, 2:4] > 0)
      and np.allclose(rows[:4, 1], lams) and np.allclose(rows[::4, 0], sizes),
      f"header '{lines[0]}', rows {rows.shape}")
k_abs, k_sca, g = mie.opacities(1e-5, 50.0e-4, 1.7 + 0.03j, 3.0)
geometric = 3.0 / (4.0 * 3.0 * 1e-5)
check("small grains absorb below the geometric opacity", 0 < k_abs < geometric and k_sca < k_abs,
      f"k_abs {k_abs:.4g}, k_sca {k_sca:.4g} cm^2/g, geometric {geometric:.4g}")

print(f"{len(checks) - len(failures)} passed, {len(failures)} failed")
sys.exit(1 if failures else 0)
