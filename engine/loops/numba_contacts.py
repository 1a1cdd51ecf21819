"""The contact points of the compiled loop of buildings that twist (numba_torsion.py): their
laws as the kernel reads them, and the solve of the points touching at a step, for one member:
numpy_torsion.solve_contacts' rule on its small dense system, by Gaussian elimination with
partial pivoting, no array allocated (the kernel hands its stack arrays)."""
import numpy as np
from numba import njit

from ..impact.contact import law_rows
from ..impact.registry import ROW_WIDTH
from ..torsion import point_laws
from .compiled import LINK


def point_arrays(contacts, points, size: int):
    """Every point's law code (B, P) int64, clear gap (B, P) m and law row (B, P, ROW_WIDTH)
    of its share of its wall's law (torsion.point_laws, the NumPy loop's; contact.law_rows)."""
    codes = np.zeros((size, points.wall.size), dtype=np.int64)
    gaps = np.zeros((size, points.wall.size))
    rows = np.zeros((size, points.wall.size, ROW_WIDTH))
    for columns, contact, flat in point_laws(contacts, points):
        n = columns.size
        codes[:, columns] = np.asarray(flat.law, dtype=np.int64).reshape(size, n)
        gaps[:, columns] = np.repeat(contact.clear_gap, n).reshape(size, n)
        rows[:, columns] = law_rows(flat).reshape(size, n, ROW_WIDTH)
    return codes, gaps, rows


@njit(**LINK)
def solve_dense(n, a, rhs, x):
    """x[:n] = a[:n, :n]^-1 rhs[:n] by Gaussian elimination with partial pivoting (a and rhs
    overwritten)."""
    for col in range(n):
        best, big = col, abs(a[col, col])
        for i in range(col + 1, n):
            if abs(a[i, col]) > big:
                best, big = i, abs(a[i, col])
        if best != col:
            for j in range(n):
                a[col, j], a[best, j] = a[best, j], a[col, j]
            rhs[col], rhs[best] = rhs[best], rhs[col]
        inv = 1.0 / a[col, col]
        for i in range(col + 1, n):
            f = a[i, col] * inv
            if f != 0.0:
                for j in range(col + 1, n):
                    a[i, j] -= f * a[col, j]
                rhs[i] -= f * rhs[col]
    for i in range(n - 1, -1, -1):
        s = rhs[i]
        for j in range(i + 1, n):
            s -= a[i, j] * x[j]
        x[i] = s / a[i, i]


@njit(**LINK)
def solve_contacts(n_points, touching, elastic, dashpot, rate_free, coupling, force, active,
                    index, a, rhs, x):
    """numpy_torsion.solve_contacts for one member: force (P,) N, >= 0, of the points
    touching (1.0 flags), the active set shrunk until none pulls."""
    for p in range(n_points):
        active[p] = touching[p]
        force[p] = 0.0
    for _ in range(n_points):
        n = 0
        for p in range(n_points):
            if active[p] != 0.0:
                index[n] = p
                n += 1
        if n == 0:
            break
        for r in range(n):
            p = index[r]
            half = 0.5 * dashpot[p]
            for c in range(n):
                a[r, c] = half * coupling[p, index[c]]
            a[r, r] = 1.0 + a[r, r]
            rhs[r] = elastic[p] + dashpot[p] * rate_free[p]
        solve_dense(n, a, rhs, x)
        pulling = False
        for r in range(n):
            force[index[r]] = x[r]
            if x[r] < 0.0:
                pulling = True
        if not pulling:
            break
        for r in range(n):
            if x[r] < 0.0:
                active[index[r]] = 0.0
    for p in range(n_points):
        force[p] = max(force[p], 0.0) if active[p] != 0.0 else 0.0
