"""numpy functions whose names differ between the numpy versions the check scripts meet."""
import numpy as np

# numpy 2.0 renamed trapz to trapezoid and later releases drop trapz; Debian bookworm's numpy 1.24 has only trapz.
trapezoid = getattr(np, "trapezoid", None) or np.trapz
