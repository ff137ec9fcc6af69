"""Shock tubes: the exact solution of the Riemann problem for an ideal gas
(Toro 2009, ch. 4), independent of the C++ solver (sph/riemann_exact), and the
figure of a run against it; used by the checks of sph_sod and sph_dustyshock
(the heavy fluid of PL15 sec. 4.2)."""
import numpy as np


def exact_riemann(left, right, gamma, xi):
    """Density, velocity, pressure at x/t = xi for states (rho, u, p)."""
    rl, ul, pl = left
    rr, ur, pr = right
    cl, cr = np.sqrt(gamma * pl / rl), np.sqrt(gamma * pr / rr)

    def f(p, rho, pk, ck):
        if p > pk:  # shock
            a, b = 2 / ((gamma + 1) * rho), (gamma - 1) / (gamma + 1) * pk
            return (p - pk) * np.sqrt(a / (p + b)), np.sqrt(a / (b + p)) * (1 - 0.5 * (p - pk) / (b + p))
        r = p / pk  # rarefaction
        return 2 * ck / (gamma - 1) * (r ** ((gamma - 1) / (2 * gamma)) - 1), r ** (-(gamma + 1) / (2 * gamma)) / (rho * ck)

    p = 0.5 * (pl + pr)
    for _ in range(100):
        fl, dl = f(p, rl, pl, cl)
        fr, dr = f(p, rr, pr, cr)
        dp = (fl + fr + ur - ul) / (dl + dr)
        p = max(p - dp, 1e-12)
        if abs(dp) < 1e-14 * p:
            break
    u = 0.5 * (ul + ur) + 0.5 * (f(p, rr, pr, cr)[0] - f(p, rl, pl, cl)[0])
    g1, g2 = (gamma - 1) / (gamma + 1), (gamma - 1) / (2 * gamma)
    out = np.zeros((3, len(xi)))
    for k, s in enumerate(xi):
        if s < u:  # left of the contact
            if p > pl:
                sh = ul - cl * np.sqrt((gamma + 1) / (2 * gamma) * p / pl + g2)
                out[:, k] = (rl, ul, pl) if s < sh else (rl * (p / pl + g1) / (g1 * p / pl + 1), u, p)
            else:
                cs = cl * (p / pl) ** g2
                if s < ul - cl:
                    out[:, k] = (rl, ul, pl)
                elif s > u - cs:
                    out[:, k] = (rl * (p / pl) ** (1 / gamma), u, p)
                else:
                    c = 2 / (gamma + 1) * (cl + (gamma - 1) / 2 * (ul - s))
                    uu = 2 / (gamma + 1) * (cl + (gamma - 1) / 2 * ul + s)
                    rho = rl * (c / cl) ** (2 / (gamma - 1))
                    out[:, k] = (rho, uu, pl * (c / cl) ** (2 * gamma / (gamma - 1)))
        else:  # right of the contact
            if p > pr:
                sh = ur + cr * np.sqrt((gamma + 1) / (2 * gamma) * p / pr + g2)
                out[:, k] = (rr, ur, pr) if s > sh else (rr * (p / pr + g1) / (g1 * p / pr + 1), u, p)
            else:
                cs = cr * (p / pr) ** g2
                if s > ur + cr:
                    out[:, k] = (rr, ur, pr)
                elif s < u + cs:
                    out[:, k] = (rr * (p / pr) ** (1 / gamma), u, p)
                else:
                    c = 2 / (gamma + 1) * (cr - (gamma - 1) / 2 * (ur - s))
                    uu = 2 / (gamma + 1) * (-cr + (gamma - 1) / 2 * ur + s)
                    rho = rr * (c / cr) ** (2 / (gamma - 1))
                    out[:, k] = (rho, uu, pr * (c / cr) ** (2 * gamma / (gamma - 1)))
    return out


def plot_tube(path, x, profiles, title):
    """Writes panels of (name, particle values, exact values or None) against x in [-0.5, 0.5]."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    order = np.argsort(x)
    fig, axes = plt.subplots(1, len(profiles), figsize=(13, 4))
    for ax, (name, q, e) in zip(axes, profiles):
        ax.plot(x[order], q[order], ".", ms=3, label="mote SPH")
        if e is not None:
            ax.plot(x[order], e[order], "-", lw=1, label="exact")
        ax.set(xlim=(-0.5, 0.5), xlabel="x", title=name)
    axes[0].legend()
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")
