"""Mie theory for homogeneous spheres (Bohren & Huffman 1983, ch. 4), to make
size- and wavelength-dependent dust opacity tables without outside data.

``efficiencies(x, m)`` gives Q_ext, Q_sca and the asymmetry factor g for size
parameter x = 2 pi a / lambda and complex refractive index m = n + i k
(k > 0 absorbs): the Riccati-Bessel functions by upward recurrence, the
logarithmic derivative D_n(m x) by downward recurrence (BH eq. 4.89), the
coefficients a_n, b_n of BH eq. 4.88, Q from BH eq. 4.61-4.62 and g from BH
eq. 4.79, summed to n_stop = x + 4 x^(1/3) + 2 (Wiscombe 1980).

``scattering_amplitudes(x, m, mu)`` gives S_1 and S_2 at mu = cos(angle)
(BH eq. 4.74), so that the cross-sections can be checked by integrating the
phase function. ``write_dsharp_table`` writes the table format that
mote::radiation::read_dsharp_table reads:
"n_a n_lambda", then rows "a[cm] lambda[um] k_abs k_sca g".
"""

import numpy as np


def _coefficients(x, m):
    """Mie coefficients a_n, b_n for n = 1 .. n_stop."""
    n_stop = int(x + 4.0 * x ** (1.0 / 3.0) + 2.0)
    y = m * x
    n_down = int(max(n_stop, abs(y))) + 16
    D = np.zeros(n_down + 1, dtype=complex)
    for n in range(n_down, 0, -1):
        D[n - 1] = n / y - 1.0 / (D[n] + n / y)
    psi_prev, psi = np.cos(x), np.sin(x)  # psi_{-1}, psi_0
    chi_prev, chi = -np.sin(x), np.cos(x)  # chi_{-1}, chi_0
    a = np.zeros(n_stop, dtype=complex)
    b = np.zeros(n_stop, dtype=complex)
    for n in range(1, n_stop + 1):
        psi_n = (2 * n - 1) / x * psi - psi_prev
        chi_n = (2 * n - 1) / x * chi - chi_prev
        xi_n, xi = complex(psi_n, -chi_n), complex(psi, -chi)
        ta = D[n] / m + n / x
        tb = D[n] * m + n / x
        a[n - 1] = (ta * psi_n - psi) / (ta * xi_n - xi)
        b[n - 1] = (tb * psi_n - psi) / (tb * xi_n - xi)
        psi_prev, psi = psi, psi_n
        chi_prev, chi = chi, chi_n
    return a, b


def efficiencies(x, m):
    """(Q_ext, Q_sca, g) of a sphere with size parameter x and index m."""
    a, b = _coefficients(float(x), complex(m))
    n = np.arange(1, len(a) + 1)
    q_ext = 2.0 / x ** 2 * np.sum((2 * n + 1) * (a + b).real)
    q_sca = 2.0 / x ** 2 * np.sum((2 * n + 1) * (abs(a) ** 2 + abs(b) ** 2))
    cross = np.sum((2 * n + 1) / (n * (n + 1)) * (a * np.conj(b)).real)
    nn = n[:-1]
    neighbours = np.sum(nn * (nn + 2) / (nn + 1) * (a[:-1] * np.conj(a[1:]) + b[:-1] * np.conj(b[1:])).real)
    g = 4.0 / (x ** 2 * q_sca) * (neighbours + cross)
    return q_ext, q_sca, g


def scattering_amplitudes(x, m, mu):
    """S_1(mu), S_2(mu) (BH eq. 4.74) at the cosines mu (array)."""
    a, b = _coefficients(float(x), complex(m))
    mu = np.asarray(mu, dtype=float)
    s1 = np.zeros(mu.shape, dtype=complex)
    s2 = np.zeros(mu.shape, dtype=complex)
    pi_prev, pi = np.zeros_like(mu), np.ones_like(mu)  # pi_0, pi_1
    for n in range(1, len(a) + 1):
        tau = n * mu * pi - (n + 1) * pi_prev
        f = (2 * n + 1) / (n * (n + 1))
        s1 += f * (a[n - 1] * pi + b[n - 1] * tau)
        s2 += f * (a[n - 1] * tau + b[n - 1] * pi)
        pi_prev, pi = pi, ((2 * n + 1) * mu * pi - (n + 1) * pi_prev) / n
    return s1, s2


def opacities(a_cm, lambda_cm, m, rho_grain):
    """k_abs, k_sca (cm^2 per g of dust) and g of spheres of radius a_cm."""
    q_ext, q_sca, g = efficiencies(2.0 * np.pi * a_cm / lambda_cm, m)
    per_mass = np.pi * a_cm ** 2 / (4.0 / 3.0 * np.pi * a_cm ** 3 * rho_grain)
    return (q_ext - q_sca) * per_mass, q_sca * per_mass, g


def write_dsharp_table(path, sizes_cm, wavelengths_um, m, rho_grain):
    """A DSHARP/cuDisc-format table for a constant refractive index m."""
    with open(path, "w") as out:
        out.write(f"{len(sizes_cm)} {len(wavelengths_um)}\n")
        for a in sizes_cm:
            for lam in wavelengths_um:
                k_abs, k_sca, g = opacities(a, lam * 1e-4, m, rho_grain)
                out.write(f"{a:.10e} {lam:.10e} {k_abs:.10e} {k_sca:.10e} {g:.10e}\n")
