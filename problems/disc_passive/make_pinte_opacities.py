#!/usr/bin/env python3
"""Write the opacity table of the Pinte et al. (2009) decks (pinte_*.toml).

    make_pinte_opacities.py [OUT.dat]

Mie theory (python/mote/mie.py, Bohren & Huffman 1983) for homogeneous
spheres of astronomical silicate with a constant refractive index, the value
near 1 um of Draine & Lee (1984) / Draine (2003), m = 1.71 + 0.03 i, and a
grain density of 3.5 g cm^-3 (Pinte et al. 2009). RBO24 sec. 4.3 take
Draine's wavelength-dependent constants through Birnstiel et al. (2018);
a constant index is what this repository can make without outside data.
Sizes: the decks' dust.sizes, 10 from 0.1 um to 0.5 cm (the MRN range up to
RBO24's 0.5 cm); wavelengths: the 101 edges of the decks' 100 stellar bins,
0.1-3000 um. The table is in the DSHARP/cuDisc format
(radiation.opacity = "dsharp"): "n_a n_lambda", then
"a[cm] lambda[um] k_abs k_sca g" rows. Takes about a minute.
"""
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "python"))
from mote import mie  # noqa: E402

REFRACTIVE_INDEX = complex(1.71, 0.03)
RHO_GRAIN = 3.5                                   # g cm^-3
SIZES_CM = np.logspace(np.log10(1e-5), np.log10(0.5), 10)
WAVELENGTHS_UM = np.logspace(np.log10(0.1), np.log10(3000.0), 101)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "pinte_opacities.dat")
    mie.write_dsharp_table(out, SIZES_CM, WAVELENGTHS_UM, REFRACTIVE_INDEX, RHO_GRAIN)
    print(f"wrote {out}: {len(SIZES_CM)} sizes x {len(WAVELENGTHS_UM)} wavelengths")


if __name__ == "__main__":
    main()
