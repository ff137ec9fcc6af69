"""Opacity tables from other tools, written in the DSHARP/cuDisc table format
that mote::radiation::read_dsharp_table reads (radiation.opacity = "dsharp"):
a line "n_a n_lambda", then n_a blocks of n_lambda rows
"a[cm] lambda[um] k_abs k_sca g", sizes and wavelengths increasing.

``from_dsharp_opac(npz, out)`` converts the opacities of the DSHARP dust
model (Birnstiel et al. 2018, ApJL 869, L45: water ice, astronomical
silicates, troilite and refractory organics) as the ``dsharp_opac`` package
stores them (``dsharp_opac/data/default_opacities_smooth.npz``: arrays ``a``
[cm], ``lam`` [cm], ``k_abs``, ``k_sca`` [cm^2/g] and ``g`` over (a, lam)).
That file is not part of mote (the package is GPL-3.0); install the package
(``pip install dsharp_opac``) or download the file, then

    python3 -m mote.opacity_tables dsharp_opac default_opacities_smooth.npz dsharp.dat

and set ``radiation.opacity_file = "dsharp.dat"``. The table keeps every
size and wavelength of the npz. mote reads g as the forward-scattering
correction k_sca (1 - g), g in [-1, 1]; the DSHARP g has values down to about
-2e-6 (round-off of isotropic scattering), written as they are.
"""

import os
import sys

import numpy as np


def write_table(path, sizes_cm, wavelengths_cm, k_abs, k_sca, g):
    """Writes the table; k_abs, k_sca and g are (n_a, n_lambda) arrays."""
    sizes_cm = np.asarray(sizes_cm, dtype=float)
    wavelengths_cm = np.asarray(wavelengths_cm, dtype=float)
    shape = (len(sizes_cm), len(wavelengths_cm))
    for name, values in (("k_abs", k_abs), ("k_sca", k_sca), ("g", g)):
        if np.shape(values) != shape:
            raise ValueError(f"{name} has shape {np.shape(values)}, expected (n_a, n_lambda) = {shape}")
    if not (np.all(np.diff(sizes_cm) > 0) and np.all(np.diff(wavelengths_cm) > 0)):
        raise ValueError("sizes and wavelengths must increase")
    if np.any(np.asarray(k_abs) < 0) or np.any(np.asarray(k_sca) < 0):
        raise ValueError("opacities must be >= 0")
    g = np.asarray(g, dtype=float)
    if np.any(np.abs(g) > 1):
        raise ValueError("the asymmetry factor g must lie in [-1, 1]")
    partial = path + ".partial"  # renamed over path when complete: an existing table is never left half written
    with open(partial, "w") as out:
        out.write(f"{shape[0]} {shape[1]}\n")
        for i, a in enumerate(sizes_cm):
            for j, lam in enumerate(wavelengths_cm):
                out.write(f"{a:.10e} {lam * 1e4:.10e} {k_abs[i][j]:.10e} {k_sca[i][j]:.10e} {g[i, j]:.10e}\n")
    os.replace(partial, path)


def from_dsharp_opac(npz_path, out_path):
    """Converts a dsharp_opac npz (a, lam in cm; k_abs, k_sca, g over (a, lam))."""
    data = np.load(npz_path)
    missing = [key for key in ("a", "lam", "k_abs", "k_sca", "g") if key not in data.files]
    if missing:
        raise ValueError(f"{npz_path}: not a dsharp_opac opacity file (no {', '.join(missing)})")
    write_table(out_path, data["a"], data["lam"], data["k_abs"], data["k_sca"], data["g"])
    return len(data["a"]), len(data["lam"])


def main(argv):
    if len(argv) != 4 or argv[1] != "dsharp_opac":
        print("usage: python3 -m mote.opacity_tables dsharp_opac IN.npz OUT.dat", file=sys.stderr)
        return 2
    try:
        n_a, n_lam = from_dsharp_opac(argv[2], argv[3])
    except (OSError, ValueError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 1
    print(f"{argv[3]}: {n_a} sizes x {n_lam} wavelengths")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
