"""Exact bilinear isolator (SPEC section 1): an elastic spring k2 in parallel with an
elastic-perfectly-plastic spring of stiffness k1 - k2 yielding at (k1 - k2) * u_y."""
import numpy as np


def plastic_spring_force(f_prev, du, k_plastic, f_yield):
    """Return-mapped force (N) of the elastic-perfectly-plastic spring after an increment du (m).

    Scalars or (B,) arrays alike (the kernel compiles this very function); the elastic trial
    force is clipped to +-f_yield, which is the exact return mapping for a perfectly plastic
    spring.
    """
    return np.minimum(np.maximum(f_prev + k_plastic * du, -f_yield), f_yield)


def isolator_force(u0, f_plastic, k2):
    """Total isolator force (N): elastic k2 branch plus the plastic spring's force (scalars or
    (B,) arrays)."""
    return k2 * u0 + f_plastic
