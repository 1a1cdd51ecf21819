"""Units: SI inside every layer; the paper's cm, mm, g, kN and kN/mm^n only at the edges.

Each constant is the SI value of one unit, so a quantity converts the same way everywhere:
    value_in_si = value_in_unit * UNIT        value_in_unit = value_in_si / UNIT
e.g. ``15 * CM`` is 0.15 m, ``accel / G`` is an acceleration in g, ``force / KN`` in kN.
"""
from __future__ import annotations

import numpy as np

G = 9.81
"""m/s^2 in 1 g: the value SPEC uses for the building weight and for records given in g (not
the standard 9.80665)."""
CM = 1e-2
"""m in 1 cm."""
MM = 1e-3
"""m in 1 mm."""
KN = 1e3
"""N in 1 kN."""
KN_PER_MM = 1e6
"""N/m in 1 kN/mm."""
TONNE = 1e3
"""kg in 1 t."""


def kn_per_mm_n(n) -> np.ndarray:
    """N/m^n in 1 kN/mm^n: the unit of a power-law contact stiffness F = k delta^n.

    1 kN/mm^n = 1e3 N / (1e-3 m)^n = 1e3 * 1e3^n N/m^n; n may be an array.
    """
    return KN * 1e3 ** np.asarray(n, dtype=float)  # 1e3 = 1 / MM, exact


def power_law_units(n) -> str:
    """Units string of a power-law stiffness F = k delta^n (N/m^n), for archives.

    UDUNITS has no fractional powers: "N m-1.5" would parse as 1.5 N/m, wrongly. An integer n
    gets the UDUNITS string ("N m-1"); any other n a string UDUNITS refuses ("N m^(-1.5)"), so
    that no reader converts it silently; say the unit in long_name as well.
    """
    n = float(n)
    return f"N m-{n:g}" if n.is_integer() else f"N m^(-{n:g})"
